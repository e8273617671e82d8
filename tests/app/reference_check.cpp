// reference_check MESH FIELD IMAGE.pfm W H STEP UNIT LO HI COLORMAP ex ey ez ax ay az ux uy uz fovy
// [max-rmse]
//                 [time-step]
// Renders MESH with the double-precision CPU reference (Grid mode: the same samples as the GPU),
// clipped by the planes of REFERENCE_CHECK_CLIP, with the opacity points of
// REFERENCE_CHECK_OPACITY, on a log scale if REFERENCE_CHECK_LOG is 1, with a parallel projection
// of scale REFERENCE_CHECK_PARALLEL_SCALE if set,
// composites over black like `render --background 0,0,0`, and compares with IMAGE.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "io/mesh_io.h"
#include "prep/prepare.h"
#include "prep/vertex_order.h"
#include "ref/reference_renderer.h"
#include "scene/image.h"

using namespace sm;

int main(int argc, char** argv) {
  if (argc < 21) {
    std::fprintf(stderr, "reference_check: needs 20 arguments (see the source)\n");
    return 2;
  }
  try {
    mesh::UnstructuredMesh input = io::readMesh(argv[1]);
    // The GPU splits quads through their smallest vertex in the global (position) order: give the
    // reference the same numbering so that warped quads are triangulated alike.
    std::vector<uint32_t> order =
        prep::globalVertexOrder(input.points, prep::makeGlobalFrame(input.bounds()));
    std::vector<uint32_t> newId(order.size());
    for (size_t i = 0; i < order.size(); ++i) newId[order[i]] = uint32_t(i);
    mesh::UnstructuredMesh m = input;
    for (size_t i = 0; i < order.size(); ++i) m.points[i] = input.points[order[i]];
    for (auto& cells : m.cells)
      for (uint32_t& v : cells) v = newId[v];
    const mesh::Field* f = input.findField(argv[2]);
    if (!f) throw std::runtime_error("no such field");
    std::vector<float> values(order.size());
    const size_t timeStep = argc > 22 ? std::strtoul(argv[22], nullptr, 10) : 0;
    for (size_t i = 0; i < order.size(); ++i) values[i] = f->steps.at(timeStep)[order[i]];
    int w = std::atoi(argv[4]), h = std::atoi(argv[5]);
    scene::TransferFunction tf = scene::makeTransferFunction(argv[10]);
    tf.unitDistance = std::atof(argv[7]);
    tf.lo = std::atof(argv[8]);
    tf.hi = std::atof(argv[9]);
    if (const char* log = std::getenv("REFERENCE_CHECK_LOG"); log && std::string(log) == "1")
      tf.scale = scene::ScalarScale::Log;
    // Opacity points from REFERENCE_CHECK_OPACITY="V:A,V:A,...", as `render --opacity` takes them.
    if (const char* opacity = std::getenv("REFERENCE_CHECK_OPACITY")) {
      std::vector<scene::OpacityPoint> points;
      for (const char* p = opacity; *p;) {
        scene::OpacityPoint op;
        int used = 0;
        if (std::sscanf(p, "%lf:%lf%n", &op.value, &op.opacity, &used) != 2)
          throw std::runtime_error(std::string("REFERENCE_CHECK_OPACITY: '") + opacity +
                                   "' is not V:A,V:A,...");
        points.push_back(op);
        p += used;
        if (*p == ',') ++p;
      }
      scene::setOpacityPoints(tf, points);
    }
    scene::Camera cam;
    cam.eye = {std::atof(argv[11]), std::atof(argv[12]), std::atof(argv[13])};
    cam.at = {std::atof(argv[14]), std::atof(argv[15]), std::atof(argv[16])};
    cam.up = {std::atof(argv[17]), std::atof(argv[18]), std::atof(argv[19])};
    cam.fovyDeg = std::atof(argv[20]);
    // A parallel projection of this scale, as `render --parallel-scale` takes it.
    if (const char* scale = std::getenv("REFERENCE_CHECK_PARALLEL_SCALE")) {
      cam.parallel = true;
      cam.parallelScale = std::atof(scale);
    }
    double maxRmse = argc > 21 ? std::atof(argv[21]) : 1.0 / 255.0;
    ref::RenderSettings rs;
    rs.dt = std::atof(argv[6]);
    // Clip planes from REFERENCE_CHECK_CLIP="px,py,pz,nx,ny,nz[;...]", as `render --clip` takes
    // them.
    if (const char* clip = std::getenv("REFERENCE_CHECK_CLIP")) {
      std::string planes = clip;
      for (size_t at = 0; at < planes.size();) {
        size_t end = std::min(planes.find(';', at), planes.size());
        scene::ClipPlane p;
        if (std::sscanf(planes.substr(at, end - at).c_str(), "%lf,%lf,%lf,%lf,%lf,%lf", &p.point.x,
                        &p.point.y, &p.point.z, &p.normal.x, &p.normal.y, &p.normal.z) != 6)
          throw std::runtime_error("REFERENCE_CHECK_CLIP: '" + planes +
                                   "' is not PX,PY,PZ,NX,NY,NZ[;...]");
        rs.clipPlanes.push_back(p);
        at = end + 1;
      }
    }
    ref::ReferenceRenderer r(m);
    scene::Image want = r.render(cam, w, h, values, tf, rs).image;
    for (auto& p : want.pixels) p = glm::vec4(glm::vec3(p), 1.0f);  // over black, as the PFM stores
    scene::Image got = scene::readPfm(argv[3]);
    scene::ImageError e = scene::compareImages(want, got);
    std::printf("GPU image vs CPU reference: RMSE %.3g (limit %.3g), max abs %.3g, PSNR %.1f dB\n",
                e.rmse, maxRmse, e.maxAbs, e.psnr);
    if (e.rmse > maxRmse || e.nanPixels) {
      scene::writePngRgba(std::string(argv[3]) + ".reference.png", want);
      scene::writePngRgba(std::string(argv[3]) + ".difference.png",
                          scene::differenceImage(want, got, 10.0f));
      return 1;
    }
    return 0;
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "reference_check: %s\n", ex.what());
    return 2;
  }
}
