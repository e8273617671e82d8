#include "mesh_renderer.h"

#include <cmath>
#include <limits>

#include "common/error.h"
#include "pipeline/render_options.h"
#include "pipeline/render_setup.h"
#include "scene/image.h"
#include "scene/transfer_function.h"
#include "scene_args.h"

namespace sm::python {
namespace api = shellmarch::insitu;

namespace {

// The points elements use (UnstructuredMesh::bounds leaves the others out, and the CLI frames
// that). Ids are valid here: setMesh checked them.
mesh::Bounds usedBounds(const api::MeshView& m) {
  const size_t n = m.points.size() / 3;
  std::vector<uint8_t> used(n, 0);
  for (const api::IndexSpan* ids : {&m.tetrahedra, &m.pyramids, &m.wedges, &m.hexahedra})
    for (size_t i = 0; i < ids->size(); ++i) used[size_t((*ids)[i])] = 1;
  mesh::Bounds b;
  for (size_t i = 0; i < n; ++i)
    if (used[i]) b.extend(glm::dvec3(m.points[3 * i], m.points[3 * i + 1], m.points[3 * i + 2]));
  return b;
}

std::array<double, 3> arr(const glm::dvec3& v) {
  return {v.x, v.y, v.z};
}

}  // namespace

MeshRenderer::MeshRenderer(std::optional<MPI_Comm> comm, const api::Options& options)
    : comm_(comm),
      renderer_(comm ? std::make_unique<api::Renderer>(*comm, options)
                     : std::make_unique<api::Renderer>(options)) {}

double MeshRenderer::reduce(double v, MPI_Op op) {
  if (!comm_) return v;
  double out = v;
  MPI_Allreduce(&v, &out, 1, MPI_DOUBLE, op, *comm_);
  return out;
}

void MeshRenderer::setMesh(const api::MeshView& mesh) {
  renderer_->setMesh(mesh);
  ranges_.clear();
  firstField_.clear();
  const mesh::Bounds local = usedBounds(mesh);
  const double inf = std::numeric_limits<double>::infinity();
  whole_ = mesh::Bounds{};
  for (int a = 0; a < 3; ++a) {
    whole_.lo[a] = reduce(local.empty ? inf : local.lo[a], MPI_MIN);
    whole_.hi[a] = reduce(local.empty ? -inf : local.hi[a], MPI_MAX);
  }
  whole_.empty = !(whole_.lo.x <= whole_.hi.x);
}

void MeshRenderer::setField(const std::string& name, std::span<const float> values) {
  renderer_->setField(name, values);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (float v : values)
    if (std::isfinite(v)) lo = std::min(lo, double(v)), hi = std::max(hi, double(v));
  ranges_[name] = {lo, hi};
  if (firstField_.empty()) firstField_ = name;
}

void MeshRenderer::setCellField(const std::string& name, std::span<const float> values) {
  renderer_->setCellField(name, values);
  ranges_[name] = {NAN, NAN};
  if (firstField_.empty()) firstField_ = name;
}

// The range --opacity's points are placed in when none was given: the field's, over all ranks,
// as the library takes it. Collective.
std::pair<double, double> MeshRenderer::opacityRange(const std::string& field) {
  auto it = ranges_.find(field);
  const bool cell = it != ranges_.end() && std::isnan(it->second.first);
  const double lo = reduce(it == ranges_.end() || cell ? INFINITY : it->second.first, MPI_MIN);
  const double hi = reduce(it == ranges_.end() || cell ? -INFINITY : it->second.second, MPI_MAX);
  if (reduce(cell ? 1.0 : 0.0, MPI_MAX) > 0)
    throw Error("--opacity: field '", field,
                "' is cell data averaged onto the points: give range= with opacity=");
  if (!(lo <= hi)) return {0.0, 1.0};  // no finite value: the library's range too
  return {lo, hi};
}

std::optional<Image8> MeshRenderer::render(const std::vector<std::string>& args) {
  const app::RenderJob job = parseSceneArgs("(mesh)", args);
  // The library draws its legend over a colour; the command's transparent legend has no
  // counterpart there.
  if (job.legend && job.transparent)
    throw Error(
        "--legend with --background transparent: not available for a shellmarch.Mesh "
        "(render the mesh from a file for it, or give a background colour)");
  api::RenderSettings s;
  s.width = job.width;
  s.height = job.height;
  s.field = job.field.empty() ? firstField_ : job.field;
  // The CLI's camera, from the same bounds.
  const scene::Camera c = session::makeCamera(app::frameRequest(job), whole_);
  s.camera = api::Camera{arr(c.eye), arr(c.at), arr(c.up), c.fovyDeg};
  s.colormap = job.colormap;
  if (job.range) s.range = std::array<double, 2>{job.range->first, job.range->second};
  s.logScale = job.logScale;
  s.opacityScale = job.opacityScale;
  s.unitDistance = job.unitDistance.value_or(0.0);
  s.sampleDistance = job.step.value_or(0.0);
  s.integration = job.integration == render::Integration::Sampled ? "sampled" : "exact";
  s.earlyTermination = job.earlyTermination;
  for (const scene::ClipPlane& p : job.clipPlanes)
    s.clipPlanes.push_back({arr(p.point), arr(p.normal)});
  s.legend = job.legend;
  s.legendBackground = {job.background.r, job.background.g, job.background.b};
  if (!job.opacityPoints.empty()) {
    // The library takes a table: the CLI's, the colour map with the points' opacity over the range.
    scene::TransferFunction tf = scene::makeTransferFunction(job.colormap);
    std::tie(tf.lo, tf.hi) = job.range ? *job.range : opacityRange(s.field);
    if (job.logScale) tf.scale = scene::ScalarScale::Log;
    scene::setOpacityPoints(tf, job.opacityPoints);
    for (const glm::vec4& e : tf.table) s.table.push_back({e.r, e.g, e.b, e.a});
  }
  const api::Image img = renderer_->render(s);
  if (img.empty()) return std::nullopt;
  scene::Image frame(img.width, img.height);
  for (size_t i = 0; i < frame.pixels.size(); ++i)
    frame.pixels[i] =
        glm::vec4(img.rgba[4 * i], img.rgba[4 * i + 1], img.rgba[4 * i + 2], img.rgba[4 * i + 3]);
  return Image8{img.width, img.height, scene::toRgba8(frame, job.imageBackground())};
}

}  // namespace sm::python
