// The in-situ API renders what the renderer renders: a known answer through the API (homogeneous
// slabs, pbrt style), the caller's vertex order honoured, and time steps that upload scalars only.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "render/render_harness.h"
#include "renderer_suite.h"
#include "scene/camera.h"
#include "scene/legend.h"
#include "shellmarch/insitu.h"
#include "sim_mesh.h"
#include "support/test_meshes.h"

namespace sm::insitu::test {
namespace {

namespace api = shellmarch::insitu;

// Ray/box intersection in double: [t0, t1] of the ray inside [lo, hi]^3, or t1 < t0.
void rayBox(glm::dvec3 o, glm::dvec3 d, double lo, double hi, double& t0, double& t1) {
  t0 = 0;
  t1 = 1e300;
  for (int a = 0; a < 3; ++a) {
    double ta = (lo - o[a]) / d[a], tb = (hi - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
}

scene::CameraFrame frameOf(const api::RenderSettings& s) {
  const api::Camera& c = *s.camera;
  return scene::cameraFrame(scene::Camera{{c.eye[0], c.eye[1], c.eye[2]},
                                          {c.at[0], c.at[1], c.at[2]},
                                          {c.up[0], c.up[1], c.up[2]},
                                          c.fovyDeg},
                            s.width, s.height);
}

float alphaAt(const api::Image& img, int x, int y) {
  return img.rgba[(size_t(y) * img.width + x) * 4 + 3];
}

using InsituApi = RendererSuite;

enum class Given { PerVertex, PerElement };

// The slab's frame: a constant field of extinction sigma seen from a corner, the whole integral
// (no early termination).
api::RenderSettings slabSettings(double sigma) {
  api::RenderSettings s;
  s.width = s.height = 40;
  s.camera = api::Camera{{1.9, 2.3, 2.7}, {0.5, 0.5, 0.5}, {0, 0, 1}, 40};
  s.table = {{0.2f, 0.6f, 1.0f, 1.0f}, {0.2f, 0.6f, 1.0f, 1.0f}};
  s.range = {0.0, 1.0};
  s.unitDistance = 1.0 / sigma;
  s.sampleDistance = 0.01;
  s.earlyTermination = 2.0;  // off: the whole integral
  return s;
}

// A unit cube of constant extinction sigma: every pixel's opacity is 1 - exp(-sigma L), whether
// the constant is given per vertex or per element.
void expectSlab(api::Renderer& vis, const mesh::UnstructuredMesh& m, const char* name,
                Given given = Given::PerVertex) {
  SimMesh sim = simMesh(m);
  vis.setMesh(sim.view());
  if (given == Given::PerVertex)
    vis.setField("density", std::vector<float>(sim.vertices(), 0.5f));
  else
    vis.setCellField("density", std::vector<float>(m.numCells(), 0.5f));
  const double sigma = 1.3;
  const api::RenderSettings s = slabSettings(sigma);
  api::Image img = vis.render(s);
  ASSERT_EQ(img.rgba.size(), size_t(s.width) * s.height * 4) << name;
  const scene::CameraFrame cam = frameOf(s);
  double maxErr = 0;
  int covered = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      double t0, t1;
      rayBox(cam.eye, cam.pixelDirection(x, y), 0.0, 1.0, t0, t1);
      const double L = t1 > t0 ? t1 - t0 : 0.0;
      covered += L > 0;
      maxErr = std::max(maxErr, std::abs(alphaAt(img, x, y) - (1.0 - std::exp(-sigma * L))));
    }
  EXPECT_GT(covered, s.width * s.height / 4) << name;
  // Within one sample of the continuous integral (slab_test.cpp checks the scheme exactly).
  EXPECT_LT(maxErr, sigma * s.sampleDistance + 1e-4) << name;
}

TEST_F(InsituApi, SlabKnownAnswerEveryElementType) {
  const uint64_t builds = vis_->stats().geometryBuilds;
  expectSlab(*vis_, sm::test::hexGrid(3), "hexahedra");
  expectSlab(*vis_, sm::test::kuhnTetGrid(3), "tetrahedra");
  expectSlab(*vis_, sm::test::wedgeGrid(2), "wedges");
  expectSlab(*vis_, sm::test::pyramidGrid(2), "pyramids");
  EXPECT_EQ(vis_->stats().geometryBuilds - builds, 4u);  // one per setMesh
}

TEST_F(InsituApi, SlabKnownAnswerFromACellField) {
  expectSlab(*vis_, sm::test::wedgeGrid(2), "wedges", Given::PerElement);
  expectSlab(*vis_, sm::test::pyramidGrid(2), "pyramids", Given::PerElement);
}

// Clip planes through the API: the slab cut at x = 0.6 (keeping x <= 0.6) and z = 0.3 (keeping
// z >= 0.3) has the opacity of the box [0, 0.6] x [0, 1] x [0.3, 1].
TEST_F(InsituApi, ClipPlanesCutTheSlab) {
  SimMesh sim = simMesh(sm::test::kuhnTetGrid(3));
  vis_->setMesh(sim.view());
  vis_->setField("density", std::vector<float>(sim.vertices(), 0.5f));
  const double sigma = 1.3;
  api::RenderSettings s = slabSettings(sigma);
  s.clipPlanes = {{{0.6, 0, 0}, {-2, 0, 0}}, {{0, 0, 0.3}, {0, 0, 1}}};
  api::Image img = vis_->render(s);
  const scene::CameraFrame cam = frameOf(s);
  double maxErr = 0;
  int covered = 0, cut = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const glm::dvec3 d = cam.pixelDirection(x, y);
      double t0, t1, c0, c1;
      rayBox(cam.eye, d, 0.0, 1.0, t0, t1);
      sm::test::rayBox(cam.eye, d, {0, 0, 0.3}, {0.6, 1, 1}, c0, c1);
      const double L = c1 > c0 ? c1 - c0 : 0.0;
      covered += L > 0;
      cut += t1 > t0 && L == 0;
      maxErr = std::max(maxErr, std::abs(alphaAt(img, x, y) - (1.0 - std::exp(-sigma * L))));
    }
  EXPECT_GT(covered, s.width * s.height / 8);
  EXPECT_GT(cut, s.width * s.height / 8);
  EXPECT_LT(maxErr, sigma * s.sampleDistance + 1e-4);
}

// A log scale through the API: density 10 over the range [1, 1000] sits a third of the way up a
// table whose opacity ramps from 0 to 1, so the slab has a third of the extinction (on a linear
// scale, under a hundredth); a range that is not positive is refused on every rank alike.
TEST_F(InsituApi, LogScaleTakesTheLogCoordinate) {
  SimMesh sim = simMesh(sm::test::hexGrid(3));
  vis_->setMesh(sim.view());
  vis_->setField("density", std::vector<float>(sim.vertices(), 10.0f));
  const double sigma = 1.3;
  api::RenderSettings s = slabSettings(3.0 * sigma);
  s.table.clear();
  for (int i = 0; i < 256; ++i) s.table.push_back({0.5f, 0.5f, 0.5f, float(i) / 255.0f});
  s.range = {1.0, 1000.0};
  s.logScale = true;
  api::Image img = vis_->render(s);
  const scene::CameraFrame cam = frameOf(s);
  double maxErr = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      double t0, t1;
      rayBox(cam.eye, cam.pixelDirection(x, y), 0.0, 1.0, t0, t1);
      const double L = t1 > t0 ? t1 - t0 : 0.0;
      maxErr = std::max(maxErr, std::abs(alphaAt(img, x, y) - (1.0 - std::exp(-sigma * L))));
    }
  EXPECT_LT(maxErr, sigma * s.sampleDistance + 1e-4);
  s.range = {0.0, 1000.0};
  try {
    vis_->render(s);
    ADD_FAILURE() << "a log scale over [0, 1000] was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("render: logScale: field '"), std::string::npos)
        << e.what();
    EXPECT_NE(
        std::string(e.what()).find("has the range 0 .. 1000, and a log scale needs a positive"),
        std::string::npos)
        << e.what();
  }
}

// The legend (RenderSettings::legend) is the one `render --legend` draws: the image without it,
// with scene::drawLegend applied for the same colour map, range, field name and background, bit
// for bit; nothing outside the legend's layout changes. A background outside [0, 1] is refused.
TEST_F(InsituApi, LegendIsTheOneRenderDraws) {
  SimMesh sim = simMesh(sm::test::hexGrid(3));
  vis_->setMesh(sim.view());
  std::vector<float> values(sim.vertices());
  for (size_t i = 0; i < values.size(); ++i) values[i] = float(i % 7);
  vis_->setField("pressure", values);
  api::RenderSettings s = slabSettings(1.3);
  s.width = 200;
  s.height = 150;
  s.table.clear();
  s.colormap = "viridis";
  s.range = {0.0, 6.0};
  const api::Image plain = vis_->render(s);
  s.legend = true;
  s.legendBackground = {1.0f, 1.0f, 1.0f};
  const api::Image legend = vis_->render(s);
  ASSERT_EQ(legend.rgba.size(), plain.rgba.size());
  scene::TransferFunction tf = scene::makeTransferFunction("viridis");
  tf.lo = 0.0;
  tf.hi = 6.0;
  scene::Image want(s.width, s.height);
  for (size_t i = 0; i < want.pixels.size(); ++i)
    want.pixels[i] = glm::vec4(plain.rgba[4 * i], plain.rgba[4 * i + 1], plain.rgba[4 * i + 2],
                               plain.rgba[4 * i + 3]);
  scene::drawLegend(want, tf, "pressure", glm::vec3(1.0f));
  const scene::LegendLayout l = scene::legendLayout(s.width, s.height, tf, "pressure");
  int changed = 0, wrong = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const size_t i = size_t(y) * s.width + x;
      const glm::vec4 got(legend.rgba[4 * i], legend.rgba[4 * i + 1], legend.rgba[4 * i + 2],
                          legend.rgba[4 * i + 3]);
      wrong += got != want.pixels[i];
      const bool differs = got != glm::vec4(plain.rgba[4 * i], plain.rgba[4 * i + 1],
                                            plain.rgba[4 * i + 2], plain.rgba[4 * i + 3]);
      changed += differs;
      if (differs) {
        EXPECT_TRUE(x >= l.left && x < l.right && y >= l.top && y < l.bottom) << x << "," << y;
      }
    }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(changed, l.barWidth * l.barHeight);
  s.legendBackground = {2.0f, 0.0f, 0.0f};
  try {
    vis_->render(s);
    ADD_FAILURE() << "a legend background of 2 was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("render: legendBackground: components must be in [0, 1]"),
              std::string::npos)
        << e.what();
  }
}

// A cell field becomes, at each vertex, the mean of the elements that use it (computed here
// independently, in the caller's shuffled vertex order), and renders as that vertex field does.
TEST_F(InsituApi, CellFieldIsTheMeanOfTheElementsAtEachVertex) {
  SimMesh sim = shuffled(simMesh(sm::test::pyramidGrid(3)), 11);
  const std::vector<float> cells =
      cellField(sim, [](glm::dvec3 c) { return float(std::sin(4 * c.x) + c.y * c.z); });
  std::vector<double> sum(sim.vertices(), 0.0), count(sim.vertices(), 0.0);
  size_t e = 0;
  for (int t = 0; t < 4; ++t) {
    const uint32_t nv = mesh::numVerts(mesh::kAllCellTypes[t]);
    for (size_t i = 0; i < sim.cells[t].size(); i += nv, ++e)
      for (uint32_t k = 0; k < nv; ++k) {
        sum[size_t(sim.cells[t][i + k])] += cells[e];
        count[size_t(sim.cells[t][i + k])] += 1;
      }
  }
  std::vector<float> means(sim.vertices());
  for (size_t v = 0; v < means.size(); ++v) means[v] = float(sum[v] / count[v]);
  vis_->setMesh(sim.view());
  const std::string byVertex = "by vertex", byElement = "by element";  // GCC 12 -Wrestrict
  vis_->setField(byVertex, means);
  vis_->setCellField(byElement, cells);
  api::RenderSettings s;
  s.width = 36;
  s.height = 28;
  s.colormap = "inferno";
  s.range = {-1.0, 2.0};
  s.field = byVertex;
  api::Image want = vis_->render(s);
  s.field = byElement;
  api::Image got = vis_->render(s);
  ASSERT_EQ(want.rgba.size(), got.rgba.size());
  double maxErr = 0, maxAlpha = 0;
  for (size_t i = 0; i < got.rgba.size(); ++i) {
    maxErr = std::max(maxErr, double(std::abs(got.rgba[i] - want.rgba[i])));
    if (i % 4 == 3) maxAlpha = std::max(maxAlpha, double(got.rgba[i]));
  }
  EXPECT_GT(maxAlpha, 0.3);
  EXPECT_LE(maxErr, 1e-6);  // the same means up to the order of summation
}

// A solver's polyhedral cells through the API: a block of cubes given as polyhedra (face streams)
// renders as the same cubes given as hexahedra, with a field per vertex and one per element (each
// polyhedron's value reaching all its tetrahedra), and a cell field of polyhedra after hexahedra
// takes its values in the caller's order: the four types, then the polyhedra.
TEST_F(InsituApi, PolyhedraRenderAsTheCellsTheyAre) {
  // Unit cubes (a 3^3 grid over [0, 3]^3), each also written as a polyhedron of its six faces.
  const SimMesh grid = simMesh(sm::test::hexGrid(3, 3.0));
  const std::vector<double>& xyz = grid.xyz;
  const std::vector<int64_t>& hexes = grid.cells[3];
  const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                           {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  std::vector<int64_t> polyhedra;
  for (size_t h = 0; h < hexes.size(); h += 8) {
    polyhedra.push_back(6);
    for (const auto& f : faces)
      polyhedra.insert(polyhedra.end(), {4, hexes[h + size_t(f[0])], hexes[h + size_t(f[1])],
                                         hexes[h + size_t(f[2])], hexes[h + size_t(f[3])]});
  }
  const std::vector<float> cells = cellField(grid, [](glm::dvec3 c) {
    const int i = int(c.x), j = int(c.y), k = int(c.z);
    return float(i + 3 * j + 9 * k % 5);
  });
  const std::vector<float> vertexField =
      grid.field([](glm::dvec3 p) { return float(p.x + 2 * p.y + 3 * p.z); });
  api::RenderSettings s;
  s.width = 40;
  s.height = 32;
  s.colormap = "viridis";
  s.earlyTermination = 2.0;
  s.sampleDistance = 0.05;  // the same samples for both (the default follows the element size)
  auto images = [&](const api::MeshView& view) {
    vis_->setMesh(view);
    vis_->setField("linear", vertexField);
    vis_->setCellField("cells", cells);
    std::vector<api::Image> out;
    for (const char* field : {"linear", "cells"}) {
      s.field = field;
      s.range = field == std::string("linear") ? std::array<double, 2>{0, 18}
                                               : std::array<double, 2>{0, 10};
      out.push_back(vis_->render(s));
    }
    return out;
  };
  api::MeshView asHexes{xyz, {}, {}, {}, hexes};
  api::MeshView asPolyhedra{xyz, {}, {}, {}, {}};
  asPolyhedra.polyhedra = polyhedra;
  const std::vector<api::Image> want = images(asHexes), got = images(asPolyhedra);
  for (size_t f = 0; f < want.size(); ++f) {
    SCOPED_TRACE(f == 0 ? "per vertex" : "per element");
    ASSERT_EQ(want[f].rgba.size(), got[f].rgba.size());
    double maxErr = 0, maxAlpha = 0;
    for (size_t i = 0; i < got[f].rgba.size(); ++i) {
      maxErr = std::max(maxErr, double(std::abs(got[f].rgba[i] - want[f].rgba[i])));
      if (i % 4 == 3) maxAlpha = std::max(maxAlpha, double(got[f].rgba[i]));
    }
    std::printf("polyhedra against hexahedra, %s: max abs %.2g\n",
                f == 0 ? "per vertex" : "per element", maxErr);
    EXPECT_GT(maxAlpha, 0.3);
    // Per vertex: trilinear and linear interpolation of a linear field agree. Per element: each
    // polyhedron counts once at a vertex, so the means there are the hexahedra's (counted once per
    // tetrahedron, 0.17 off), and this field's means interpolate alike both ways.
    EXPECT_LE(maxErr, 1e-4);
  }
  // The first hexahedron given as such, the other 26 as polyhedra: values in the caller's order.
  const std::vector<int64_t> firstHex(hexes.begin(), hexes.begin() + 8);
  api::MeshView mixed{xyz, {}, {}, {}, firstHex};
  const std::vector<int64_t> rest(polyhedra.begin() + 31, polyhedra.end());
  mixed.polyhedra = rest;
  const std::vector<api::Image> mixedImages = images(mixed);
  double maxErr = 0;
  for (size_t i = 0; i < mixedImages[1].rgba.size(); ++i)
    maxErr = std::max(maxErr, double(std::abs(mixedImages[1].rgba[i] - want[1].rgba[i])));
  EXPECT_LE(maxErr, 1e-4);
}

// Vertices in the simulation's own (here shuffled) order give the image of the same mesh rendered
// directly: the API maps values through its own vertex order, not the caller's.
TEST_F(InsituApi, CallerVertexOrderIsHonoured) {
  const mesh::UnstructuredMesh m = sm::test::pyramidGrid(3);
  auto f = [](glm::dvec3 p) { return float(p.x + 2 * p.y - p.z); };
  SimMesh sim = shuffled(simMesh(m), 7);
  vis_->setMesh(sim.view());
  vis_->setField("f", sim.field(f));
  api::RenderSettings s;
  s.width = 36;
  s.height = 28;
  s.camera = api::Camera{{2.2, -1.4, 1.9}, {0.5, 0.5, 0.5}, {0, 0, 1}, 35};
  s.colormap = "viridis";
  s.range = {-1.0, 3.0};
  s.unitDistance = 0.4;
  s.sampleDistance = 0.02;
  api::Image img = vis_->render(s);

  render::RenderSettings direct;
  direct.width = s.width;
  direct.height = s.height;
  direct.camera = scene::Camera{{2.2, -1.4, 1.9}, {0.5, 0.5, 0.5}, {0, 0, 1}, 35};
  direct.transferFunction = scene::makeTransferFunction("viridis");
  direct.transferFunction.lo = -1.0;
  direct.transferFunction.hi = 3.0;
  direct.transferFunction.unitDistance = 0.4;
  direct.dt = 0.02;
  direct.earlyTermination = s.earlyTermination;
  std::vector<float> values(m.numPoints());
  for (size_t i = 0; i < values.size(); ++i) values[i] = f(m.points[i]);
  sm::test::GpuRender ref = sm::test::renderOnGpu(m, values, direct);
  ASSERT_EQ(ref.image.pixels.size() * 4, img.rgba.size());
  double maxErr = 0, maxAlpha = 0;
  for (size_t i = 0; i < img.rgba.size(); ++i) {
    maxErr = std::max(maxErr, double(std::abs(img.rgba[i] - ref.image.pixels[i / 4][i % 4])));
    if (i % 4 == 3) maxAlpha = std::max(maxAlpha, double(img.rgba[i]));
  }
  EXPECT_GT(maxAlpha, 0.3);  // something to compare
  EXPECT_LE(maxErr, 1e-6);   // the same prepared data and samples: equal up to nothing
}

// A time step uploads the new scalars of the field rendered, nothing else: the geometry is built
// once, an unchanged field is not uploaded again, and the image follows the new values.
TEST_F(InsituApi, TimeStepsUploadScalarsOnly) {
  SimMesh sim = simMesh(sm::test::hexGrid(3));
  vis_->setMesh(sim.view());
  const api::Stats before = vis_->stats();
  api::RenderSettings s;
  s.width = s.height = 9;
  s.camera = api::Camera{{0.5, 0.5, 3.0}, {0.5, 0.5, 0.5}, {0, 1, 0}, 20};
  s.table = {{1, 1, 1, 0}, {1, 1, 1, 1}};  // opacity = value over [0, 1]
  s.range = {0.0, 1.0};
  s.unitDistance = 1.0;
  s.sampleDistance = 0.01;
  s.earlyTermination = 2.0;
  double t0, t1;
  rayBox(frameOf(s).eye, frameOf(s).pixelDirection(4, 4), 0.0, 1.0, t0, t1);
  auto expectCentre = [&](const api::Image& img, double value) {
    EXPECT_NEAR(alphaAt(img, 4, 4), 1.0 - std::exp(-value * (t1 - t0)), value * 0.01 + 1e-4);
  };
  auto constant = [&](float v) { return std::vector<float>(sim.vertices(), v); };
  auto uploads = [&] { return vis_->stats().scalarUploads - before.scalarUploads; };

  // Names as strings: assigning a literal to s.field trips GCC 12's -Wrestrict false positive.
  const std::string a = "a", b = "b";
  vis_->setField(a, constant(0.2f));
  expectCentre(vis_->render(s), 0.2);
  vis_->setField(a, constant(0.8f));  // the next step of the same field
  expectCentre(vis_->render(s), 0.8);
  EXPECT_EQ(uploads(), 2u);
  vis_->setField(b, constant(0.5f));
  s.field = a;  // b changed, a did not: nothing to upload
  expectCentre(vis_->render(s), 0.8);
  EXPECT_EQ(uploads(), 2u);
  s.field = b;
  expectCentre(vis_->render(s), 0.5);
  expectCentre(vis_->render(s), 0.5);
  EXPECT_EQ(uploads(), 3u);
  EXPECT_EQ(vis_->stats().geometryBuilds, before.geometryBuilds);  // none since setMesh
}

// Rendering into an image reuses its storage, frame after frame, and gives what render returns.
TEST_F(InsituApi, RenderIntoReusesTheImage) {
  SimMesh sim = simMesh(sm::test::hexGrid(3));
  vis_->setMesh(sim.view());
  vis_->setField("p", std::vector<float>(sim.vertices(), 0.6f));
  api::RenderSettings s;
  s.width = 24;
  s.height = 16;
  s.camera = api::Camera{{1.9, 2.3, 2.7}, {0.5, 0.5, 0.5}, {0, 0, 1}, 40};
  s.range = {0.0, 1.0};
  api::Image into;
  vis_->render(s, into);
  ASSERT_EQ(into.width, 24);
  ASSERT_EQ(into.height, 16);
  ASSERT_EQ(into.rgba.size(), size_t(24 * 16 * 4));
  const float* storage = into.rgba.data();
  vis_->setField("p", std::vector<float>(sim.vertices(), 0.3f));
  vis_->render(s, into);
  EXPECT_EQ(into.rgba.data(), storage);  // no new allocation
  const api::Image returned = vis_->render(s);
  EXPECT_EQ(returned.rgba, into.rgba);
  float covered = 0;
  for (size_t i = 3; i < into.rgba.size(); i += 4) covered += into.rgba[i];
  EXPECT_GT(covered, 0.0f);
  // A smaller frame fits in the same storage.
  s.width = 12;
  vis_->render(s, into);
  EXPECT_EQ(into.rgba.data(), storage);
  EXPECT_EQ(into.rgba.size(), size_t(12 * 16 * 4));
}

}  // namespace
}  // namespace sm::insitu::test
