// The public classes of shellmarch/insitu.h: Renderer, a facade over prep, render and the
// compositor, and Image.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include "border/cell_averager.h"
#include "comm/reductions.h"
#include "common/error.h"
#include "common/hash.h"
#include "common/timer.h"
#include "field_store.h"
#include "frame_settings.h"
#include "group.h"
#include "mesh_input.h"
#include "prep/prepare.h"
#include "scene/image.h"
#include "scene/legend.h"
#include "scene/view_defaults.h"
#include "session/frame_request.h"
#include "session/rank_session.h"
#include "shellmarch/insitu.h"

namespace shellmarch::insitu {

using sm::insitu::FieldStore;
using sm::insitu::Group;
using sm::insitu::MeshFrame;

// Hidden: the implementation is no part of the library's interface (the class around it is).
struct __attribute__((visibility("hidden"))) Renderer::Impl {
  Impl(Group&& g, const Options& options) : group(std::move(g)) {
    group.agree([&] {
      sm::vk::ContextOptions o;
      o.device = options.device;
      o.validation = options.validation;
      o.tracer = sm::vk::parseTracer("tracer", options.tracer);
      session = std::make_unique<sm::session::RankSession>(o, sm::comm::withPeers(group.comm()));
    });
  }

  void setMesh(const MeshView& view);
  void setCellField(const std::string& name, std::span<const float> values);
  void render(const RenderSettings& settings, Image& into);
  MeshFrame agreeOnFrame(const sm::mesh::UnstructuredMesh& m);
  void upload(sm::mesh::UnstructuredMesh& m, std::vector<uint64_t> globalIds);
  void releaseMesh();

  // Declaration order is destruction order reversed: the session goes before the group.
  Group group;
  std::unique_ptr<sm::session::RankSession> session;
  std::vector<glm::vec4> pixels;  // the composited image's storage, handed from frame to frame
  FieldStore fields;
  sm::border::CellAverager cellFields;
  MeshFrame frame;
  uint64_t localElements = 0;
  // The caller's elements (setCellField's values) and, with polyhedra, which of them each of the
  // mesh's elements came from (a polyhedron's value goes to each of its tetrahedra).
  uint64_t callerElements = 0;
  std::vector<uint32_t> elementOrigin;
  double prepareSeconds = 0, frameMs = 0;
};

void Renderer::Impl::releaseMesh() {
  session->releaseScene();
  fields = FieldStore();
  cellFields = sm::border::CellAverager();
  callerElements = 0;
  elementOrigin.clear();
}

MeshFrame Renderer::Impl::agreeOnFrame(const sm::mesh::UnstructuredMesh& m) {
  const double inf = std::numeric_limits<double>::infinity();
  const sm::mesh::Bounds local = m.bounds();
  MeshFrame f;
  for (int a = 0; a < 3; ++a) {
    f.whole.lo[a] = sm::comm::minOf(group.comm(), local.empty ? inf : local.lo[a]);
    f.whole.hi[a] = sm::comm::maxOf(group.comm(), local.empty ? -inf : local.hi[a]);
  }
  f.whole.empty = !(f.whole.lo.x <= f.whole.hi.x);
  const sm::scene::ElementSizeSum sizes = sm::scene::elementSizeSum(m);
  f.elements = sm::comm::sumOf(group.comm(), sizes.count);
  f.meanElementSize =
      f.elements ? sm::comm::sumOf(group.comm(), sizes.sum) / double(f.elements) : 0.0;
  return f;
}

void Renderer::Impl::upload(sm::mesh::UnstructuredMesh& m, std::vector<uint64_t> globalIds) {
  const uint64_t inputVertices = m.numPoints();  // preparation takes the points out of m
  callerElements = m.cellOrigin.empty() ? m.numCells() : m.fileCells;
  cellFields = sm::border::CellAverager(m, std::move(globalIds));
  elementOrigin = std::move(m.cellOrigin);
  sm::prep::PreparedRank prepared =
      sm::prep::prepareRank(m, sm::prep::makeGlobalFrame(frame.whole), sm::prep::PrepOptions{})
          .rank;
  session->setScene(prepared, std::move(prepared.positions));
  localElements = prepared.numElements();
  // The device holds the geometry now; the host keeps only the vertex map for the fields.
  sm::prep::PreparedRank vertexMap;
  vertexMap.vertexSource = std::move(prepared.vertexSource);
  fields = FieldStore(std::move(vertexMap), inputVertices);
}

void Renderer::Impl::setMesh(const MeshView& view) {
  releaseMesh();
  sm::Timer timer;
  sm::mesh::UnstructuredMesh m;
  std::vector<uint64_t> globalIds;
  group.agree([&] {
    m = sm::insitu::meshFromView(view);
    globalIds = sm::insitu::globalIdsFromView(view);
  });
  // Vertices named by id on one rank and by coordinates on another would never meet.
  const bool hasVertices = m.numPoints() > 0;
  const double byId = sm::comm::maxOf(group.comm(), hasVertices && !globalIds.empty() ? 1.0 : 0.0);
  const double byPosition =
      sm::comm::maxOf(group.comm(), hasVertices && globalIds.empty() ? 1.0 : 0.0);
  if (byId > 0 && byPosition > 0)
    throw Error(
        "setMesh: globalIds given on some ranks but not on others (give them on every rank that "
        "holds vertices, or on none)");
  frame = agreeOnFrame(m);
  if (frame.elements == 0)
    throw Error("setMesh: no tetrahedra, pyramids, wedges, hexahedra or polyhedra on any rank");
  group.agree([&] { upload(m, std::move(globalIds)); });
  prepareSeconds = timer.seconds();
}

void Renderer::Impl::setCellField(const std::string& name, std::span<const float> values) {
  group.agree([&] {
    if (!session->hasScene()) throw Error("setCellField: no mesh (call setMesh first)");
    if (name.empty()) throw Error("setCellField: the field needs a name");
    if (values.size() != callerElements)
      throw Error(sm::concat("setCellField '", name, "': ", values.size(), " values for ",
                             callerElements,
                             " elements (one per element: the tetrahedra, then the pyramids, "
                             "wedges, hexahedra and polyhedra given to setMesh)"));
  });
  std::vector<float> expanded;
  if (!elementOrigin.empty()) {
    expanded.resize(elementOrigin.size());
    for (size_t i = 0; i < expanded.size(); ++i) expanded[i] = values[elementOrigin[i]];
    values = expanded;
  }
  if (!sm::comm::allSame(group.comm(), sm::hashBytes(name.data(), name.size())))
    throw Error(
        "setCellField: the field name differs between ranks; every rank must set the same cell "
        "field in the same call");
  std::vector<float> atVertices;
  group.runOrAbort([&] { atVertices = cellFields.toPoints(values, group.comm()); });
  group.agree([&] { fields.set(name, atVertices); });
}

void Renderer::Impl::render(const RenderSettings& s, Image& into) {
  sm::Timer timer;
  sm::session::FrameRequest request;
  sm::insitu::FieldRange range;
  group.agree([&] {
    if (!session->hasScene()) throw Error("render: no mesh (setMesh was not called or failed)");
    sm::insitu::inApiTerms([&] {
      request = sm::insitu::frameRequest(s);
      sm::session::checkRequest(request);
    });
    range = fields.prepare(s.field, session->scene());
  });
  if (!sm::comm::allSame(group.comm(), sm::insitu::settingsDigest(s)))
    throw Error("render: the settings differ between ranks; every rank must pass the same");
  double lo = s.range ? (*s.range)[0] : sm::comm::minOf(group.comm(), range.lo);
  double hi = s.range ? (*s.range)[1] : sm::comm::maxOf(group.comm(), range.hi);
  if (!(lo <= hi)) lo = 0, hi = 1;  // no finite value anywhere: any range renders transparent
  // Every rank has the same request, mesh frame and range: they refuse it alike.
  sm::render::RenderSettings rs;
  const std::string field = s.field.empty() ? fields.firstName() : s.field;
  group.agree([&] {
    sm::insitu::inApiTerms([&] {
      rs = sm::session::makeRenderSettings(request, sm::insitu::dataExtent(frame), field, {lo, hi});
    });
    session->renderer(s.width, s.height);  // the compositor's lists, allocated here
  });
  sm::render::FrameResult result;
  group.runOrAbort([&] { result = session->render(rs, std::move(pixels)); });
  if (group.rank() == 0 && s.legend) {  // titled as the field was asked for
    sm::scene::Image img(s.width, s.height);
    img.pixels = std::move(result.pixels);
    const std::array<float, 3>& b = s.legendBackground;
    sm::scene::drawLegend(img, rs.transferFunction, field, glm::vec3(b[0], b[1], b[2]));
    result.pixels = std::move(img.pixels);
  }
  frameMs = timer.seconds() * 1e3;
  if (group.rank() == 0) {
    into.width = s.width;
    into.height = s.height;
    into.rgba.resize(result.pixels.size() * 4);  // within its capacity from the second frame on
    std::memcpy(into.rgba.data(), result.pixels.data(), into.rgba.size() * sizeof(float));
  } else {
    into = Image{};
  }
  pixels = std::move(result.pixels);
}

namespace {

// Every exception leaves the library as Error (internal types are not part of the API).
template <typename F>
auto translated(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(e.what());
  }
}

}  // namespace

Renderer::Renderer(MPI_Comm comm, const Options& options)
    : impl_(translated([&] { return std::make_unique<Impl>(Group(comm), options); })) {}

Renderer::Renderer(const Options& options)
    : impl_(translated([&] { return std::make_unique<Impl>(Group(), options); })) {}

Renderer::~Renderer() = default;

int Renderer::rank() const {
  return impl_->group.rank();
}

int Renderer::ranks() const {
  return impl_->group.size();
}

void Renderer::setMesh(const MeshView& mesh) {
  translated([&] { impl_->setMesh(mesh); });
}

void Renderer::setField(const std::string& name, std::span<const float> values) {
  translated([&] { impl_->fields.set(name, values); });
}

void Renderer::setCellField(const std::string& name, std::span<const float> values) {
  translated([&] { impl_->setCellField(name, values); });
}

Image Renderer::render(const RenderSettings& settings) {
  Image img;
  render(settings, img);
  return img;
}

void Renderer::render(const RenderSettings& settings, Image& into) {
  translated([&] { impl_->render(settings, into); });
}

Stats Renderer::stats() const {
  const Impl& d = *impl_;
  Stats s;
  const sm::vk::Context& ctx = d.session->context();
  s.deviceName = ctx.deviceName();
  s.tracer = sm::vk::tracerName(ctx.tracer());
  s.geometryBuilds = d.session->geometryBuilds();
  s.scalarUploads = d.session->scalarUploads();
  if (d.session->hasScene()) {
    s.vertices = d.session->scene().numVertices();
    s.shellTriangles = d.session->scene().shellTriangles();
    s.elements = d.localElements;
  }
  s.validationErrors = ctx.validationErrors();
  s.validationWarnings = ctx.validationWarnings();
  s.prepareSeconds = d.prepareSeconds;
  s.frameMs = d.frameMs;
  return s;
}

namespace {

uint8_t toByte(float v) {
  if (!std::isfinite(v)) return 0;
  return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

}  // namespace

std::vector<uint8_t> Image::toRgba8() const {
  std::vector<uint8_t> out(rgba.size());
  for (size_t i = 0; i < rgba.size(); ++i) out[i] = toByte(rgba[i]);
  return out;
}

namespace {

void writeImagePng(const Image& image, const std::string& path,
                   const sm::scene::Background& background) {
  if (image.empty()) throw Error(path + ": no image to write (images exist on rank 0 only)");
  sm::scene::Image img(image.width, image.height);
  const std::vector<float>& rgba = image.rgba;
  for (size_t i = 0; i < img.pixels.size(); ++i)
    img.pixels[i] = glm::vec4(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2], rgba[4 * i + 3]);
  translated([&] { sm::scene::writePng(path, img, background); });
}

}  // namespace

void Image::writePng(const std::string& path, std::array<float, 3> background) const {
  writeImagePng(*this, path, glm::vec3(background[0], background[1], background[2]));
}

void Image::writeTransparentPng(const std::string& path) const {
  writeImagePng(*this, path, std::nullopt);
}

}  // namespace shellmarch::insitu
