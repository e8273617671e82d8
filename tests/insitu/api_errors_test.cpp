// Bad input through the in-situ API: every mistake a simulation can make with its arrays or
// settings is an Error whose message names the array, element and value at fault, and the
// renderer stays usable afterwards.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "renderer_suite.h"
#include "shellmarch/insitu.h"
#include "sim_mesh.h"
#include "support/test_meshes.h"

namespace sm::insitu::test {
namespace {

namespace api = shellmarch::insitu;

// Runs fn, expecting an api::Error whose message contains `part`.
template <typename F>
void expectError(F&& fn, const std::string& part) {
  try {
    fn();
    ADD_FAILURE() << "no error; expected one containing: " << part;
  } catch (const api::Error& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos)
        << "message: " << e.what() << "\nexpected it to contain: " << part;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an api::Error: " << e.what();
  }
}

// Two tetrahedra sharing a face, as plain arrays.
const std::vector<double> kPoints = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
const std::vector<int32_t> kTets = {0, 1, 2, 3, 1, 2, 3, 4};

api::MeshView twoTets(std::span<const double> points, std::span<const int32_t> tets) {
  api::MeshView v;
  v.points = points;
  v.tetrahedra = tets;
  return v;
}

api::RenderSettings small() {
  api::RenderSettings s;
  s.width = s.height = 8;
  return s;
}

using InsituErrors = RendererSuite;

TEST_F(InsituErrors, MeshArrays) {
  api::Renderer& r = *vis_;
  std::vector<double> p = kPoints;
  p.pop_back();
  expectError([&] { r.setMesh(twoTets(p, kTets)); },
              "setMesh: points holds 14 values, not a multiple of 3");
  std::vector<int32_t> t = kTets;
  t[6] = 9;
  expectError([&] { r.setMesh(twoTets(kPoints, t)); },
              "setMesh: tetrahedron 1 (tetrahedra[6]) refers to vertex 9, but points gives 5");
  t[6] = -1;
  expectError([&] { r.setMesh(twoTets(kPoints, t)); }, "refers to vertex -1");
  t = kTets;
  t.push_back(0);
  expectError([&] { r.setMesh(twoTets(kPoints, t)); },
              "setMesh: tetrahedra holds 9 ids, not a multiple of 4");
  t = kTets;
  t[5] = 1;
  expectError([&] { r.setMesh(twoTets(kPoints, t)); }, "uses the same point twice");
  // Polyhedra's face streams, named by polyhedron and array position.
  auto withPolyhedra = [&](std::vector<int64_t> stream) {
    api::MeshView v = twoTets(kPoints, kTets);
    v.polyhedra = stream;
    r.setMesh(v);
  };
  const std::vector<int64_t> tet = {4, 3, 0, 2, 1, 3, 0, 1, 3, 3, 1, 2, 3, 3, 2, 0, 3};
  expectError(
      [&] {
        withPolyhedra({0, 3, 0, 1, 2});
      },
      "setMesh: polyhedron 0 (polyhedra[0]) claims 0 faces");
  expectError(
      [&] {
        withPolyhedra({5, 3, 0, 1});
      },
      "setMesh: polyhedron 0 (polyhedra[0]) claims 5 faces");
  // A cell whose faces do not close (three of the tetrahedron's four) is skipped, as files' are;
  // the whole tetrahedron after it is kept.
  std::vector<int64_t> open(tet.begin(), tet.begin() + 13);
  open[0] = 3;
  open.insert(open.end(), tet.begin(), tet.end());
  const std::vector<int32_t> second(kTets.begin() + 4, kTets.end());
  api::MeshView oneTet = twoTets(kPoints, second);
  oneTet.polyhedra = open;
  r.setMesh(oneTet);
  EXPECT_EQ(r.stats().elements, 2u);
  std::vector<int64_t> bad = tet;
  bad[4] = 9;
  expectError([&] { withPolyhedra(bad); },
              "setMesh: polyhedron 0 (polyhedra[0]) refers to vertex 9 (polyhedra[4]), but points "
              "gives 5 vertices");
  bad = tet;
  bad[1] = 2;
  expectError([&] { withPolyhedra(bad); }, "face 0 claims 2 vertices (at least 3)");
  bad = tet;
  bad.pop_back();
  expectError([&] { withPolyhedra(bad); }, "face 3 claims 3 vertices, past the end");
  bad = tet;
  bad.insert(bad.end(), {4, 3, 0});
  expectError([&] { withPolyhedra(bad); }, "setMesh: polyhedron 1 (polyhedra[17]) claims 4 faces");
  bad = tet;
  bad[3] = 0;
  expectError([&] { withPolyhedra(bad); }, "(polyhedron): face 0 uses point 0 twice");
  const std::vector<uint64_t> huge = {0, 1, 2, std::numeric_limits<uint64_t>::max()};
  api::MeshView v = twoTets(kPoints, {});
  v.tetrahedra = huge;
  expectError([&] { r.setMesh(v); }, "refers to vertex -1");
  api::MeshView pyramids = twoTets(kPoints, {});
  pyramids.pyramids = kTets;  // 8 ids: not whole pyramids
  expectError([&] { r.setMesh(pyramids); }, "pyramids holds 8 ids, not a multiple of 5");
}

TEST_F(InsituErrors, NonFinitePositions) {
  for (double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    std::vector<double> p = kPoints;
    p[7] = bad;
    expectError([&] { vis_->setMesh(twoTets(p, kTets)); },
                "setMesh: point 2 has a non-finite coordinate");
  }
}

TEST_F(InsituErrors, NoElements) {
  expectError([&] { vis_->setMesh(twoTets(kPoints, {})); },
              "setMesh: no tetrahedra, pyramids, wedges, hexahedra or polyhedra on any rank");
}

// A failed setMesh leaves the renderer without a mesh (whatever an earlier test left).
void dropMesh(api::Renderer& r) {
  EXPECT_THROW(r.setMesh(twoTets(kPoints, {})), api::Error);
}

TEST_F(InsituErrors, Fields) {
  dropMesh(*vis_);
  expectError([&] { vis_->setField("t", std::vector<float>(5)); },
              "setField: no mesh (call setMesh first)");
  vis_->setMesh(twoTets(kPoints, kTets));
  expectError([&] { vis_->setField("t", std::vector<float>(4)); },
              "setField: field 't' has 4 values, but setMesh gave 5 vertices");
  expectError([&] { vis_->setField("", std::vector<float>(5)); }, "the field needs a name");
  expectError([&] { vis_->render(small()); }, "render: no field on this rank");
  vis_->setField("t", std::vector<float>(5, 1.0f));
  api::RenderSettings s = small();
  s.field = "pressure";
  expectError([&] { vis_->render(s); }, "render: no field 'pressure' on this rank (set: 't')");
}

TEST_F(InsituErrors, CellFields) {
  dropMesh(*vis_);
  expectError([&] { vis_->setCellField("p", std::vector<float>(2)); },
              "setCellField: no mesh (call setMesh first)");
  vis_->setMesh(twoTets(kPoints, kTets));
  expectError([&] { vis_->setCellField("p", std::vector<float>(5)); },
              "setCellField 'p': 5 values for 2 elements (one per element: the tetrahedra, then "
              "the pyramids, wedges, hexahedra and polyhedra given to setMesh)");
  expectError([&] { vis_->setCellField("", std::vector<float>(2)); },
              "setCellField: the field needs a name");
  const std::vector<int64_t> fourIds = {0, 1, 2, 3}, negative = {0, 1, -2, 3, 4};
  api::MeshView v = twoTets(kPoints, kTets);
  v.globalIds = fourIds;
  expectError([&] { vis_->setMesh(v); },
              "setMesh: globalIds holds 4 ids for 5 vertices (one per vertex, or none)");
  v.globalIds = negative;
  expectError([&] { vis_->setMesh(v); },
              "setMesh: globalIds[2] is -2; global ids are not negative");
  vis_->setMesh(twoTets(kPoints, kTets));
  const std::string name = "p";  // a literal assigned to s.field trips GCC 12's -Wrestrict
  vis_->setCellField(name, std::vector<float>{1.0f, 3.0f});
  api::RenderSettings s = small();
  s.field = name;
  EXPECT_FALSE(vis_->render(s).empty());  // usable after the errors
}

TEST_F(InsituErrors, Settings) {
  dropMesh(*vis_);
  expectError([&] { vis_->render(small()); }, "render: no mesh");
  vis_->setMesh(twoTets(kPoints, kTets));
  vis_->setField("t", std::vector<float>{0, 1, 2, 3, 4});
  auto expectSettingError = [&](auto change, const std::string& part) {
    api::RenderSettings s = small();
    change(s);
    expectError([&] { vis_->render(s); }, part);
  };
  expectSettingError([](auto& s) { s.width = 0; },
                     "render: width/height: 0x8 is not a usable image size");
  expectSettingError([](auto& s) { s.view = "diagonal"; }, "render: view: unknown view 'diagonal'");
  expectSettingError(
      [](auto& s) {
        s.camera = api::Camera{{1, 1, 1}, {1, 1, 1}};
      },
      "render: camera.at: 1,1,1 is the eye's position");
  expectSettingError(
      [](auto& s) {
        s.camera = api::Camera{{0, 0, 5}, {0, 0, 0}, {0, 0, 1}};
      },
      "render: camera.up: 0,0,1 is parallel to the viewing direction");
  expectSettingError(
      [](auto& s) {
        s.range = std::array<double, 2>{2, 1};
      },
      "render: range: [2, 1] must be finite with lo <= hi");
  expectSettingError(
      [](auto& s) {
        s.table = {{0, 0, 0, 2}, {0, 0, 0, 0}};
      },
      "render: table: entries must be in [0, 1], not 2");
  expectSettingError([](auto& s) { s.colormap = "no-such-map"; },
                     "render: colormap: unknown colour map 'no-such-map'; give a built-in name");
  expectSettingError([](auto& s) { s.sampleDistance = std::nan(""); },
                     "render: sampleDistance: nan must be finite");
  expectSettingError(
      [](auto& s) {
        s.clipPlanes = {{{0, 0, 0}, {0, 0, 0}}};
      },
      "render: clipPlanes: clip plane 1 has a zero normal");
  expectSettingError([](auto& s) { s.clipPlanes.resize(7); },
                     "render: clipPlanes: 7 clip planes, at most 6");
  // Finer than float positions along the rays resolve (the sample index could wrap).
  expectSettingError([](auto& s) { s.sampleDistance = 1e-12; },
                     "render: sampleDistance: 1e-12 is finer than float distances");
  // Longer than the data: most rays would take no sample and the image would be empty (sampled
  // integration: element-exact takes no samples).
  expectSettingError(
      [](auto& s) {
        s.integration = "sampled";
        s.sampleDistance = 1e6;
      },
      "render: sampleDistance: 1e+06 is longer than the data's diagonal");
  expectSettingError([](auto& s) { s.integration = "linear"; },
                     "render: integration: 'linear' is not exact or sampled");
}

// Options::tracer: a name it does not know is refused; each tracer the device offers renders the
// same image, and stats() says which rendered.
TEST(InsituTracer, EachTracerRendersTheSameImageAndABadNameIsRefused) {
  api::Options bad;
  bad.tracer = "rtx";
  expectError([&] { api::Renderer r(bad); }, "tracer: 'rtx' is not auto, query or pipeline");
  SimMesh sim = simMesh(sm::test::hexGrid(2));
  std::vector<float> field(sim.vertices());
  for (size_t i = 0; i < field.size(); ++i) field[i] = float(i % 5);
  std::vector<std::vector<float>> images;
  for (const char* tracer : {"query", "pipeline"}) {
    api::Options o;
    o.tracer = tracer;
    std::unique_ptr<api::Renderer> r;
    try {
      r = std::make_unique<api::Renderer>(o);
    } catch (const api::Error& e) {
      std::printf("%s tracer not offered here: %s\n", tracer, e.what());
      continue;
    }
    EXPECT_EQ(r->stats().tracer, tracer);
    r->setMesh(sim.view());
    r->setField("t", field);
    images.push_back(r->render(small()).rgba);
    EXPECT_EQ(r->stats().validationErrors, 0u);
  }
  ASSERT_FALSE(images.empty());
  if (images.size() == 2) {
    EXPECT_EQ(images[0], images[1]);
  }
}

// After any of these errors the renderer renders as if they had not happened.
TEST_F(InsituErrors, UsableAfterErrors) {
  std::vector<int32_t> bad = kTets;
  bad[0] = 99;
  EXPECT_THROW(vis_->setMesh(twoTets(kPoints, bad)), api::Error);
  SimMesh sim = simMesh(sm::test::hexGrid(2));
  const uint64_t builds = vis_->stats().geometryBuilds;
  vis_->setMesh(sim.view());
  EXPECT_THROW(vis_->setField("t", std::vector<float>(3)), api::Error);
  vis_->setField("t", std::vector<float>(sim.vertices(), 1.0f));
  api::RenderSettings s = small();
  s.width = 0;
  EXPECT_THROW(vis_->render(s), api::Error);
  api::Image img = vis_->render(small());
  ASSERT_EQ(img.width, 8);
  EXPECT_GT(img.rgba[(4 * 8 + 4) * 4 + 3], 0.1f);  // the default view frames the mesh
  EXPECT_EQ(vis_->stats().geometryBuilds - builds, 1u);
}

}  // namespace
}  // namespace sm::insitu::test
