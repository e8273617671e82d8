// The meshes other tools wrote (../shared/data: VTK's example cells, the "can" and "notch" data
// sets, a tetrahedral CFD result) rendered on the GPU against the CPU reference at the default
// tolerance, each with its own first field (or a linear one when it has none) over its range.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "io/mesh_io.h"
#include "render_harness.h"
#include "scene/camera.h"
#include "scene/view_defaults.h"
#include "support/test_support.h"

namespace sm::render {
namespace {

void expectMatchesReference(const std::string& file) {
  mesh::UnstructuredMesh m = io::readMesh(test::sharedDataPath(file));
  ASSERT_GT(m.numCells(), 0u) << file;
  std::vector<float> values;
  if (!m.fields.empty()) {
    values = m.fields[0].steps[0];
  } else {
    const glm::dvec3 lo = m.bounds().lo, ext = m.bounds().extent();
    for (const auto& p : m.points)
      values.push_back(float(glm::dot((p - lo) / ext, glm::dvec3(1, 2, 3)) / 6.0));
  }
  float lo = values[0], hi = values[0];
  for (float v : values) lo = std::min(lo, v), hi = std::max(hi, v);
  RenderSettings s;
  s.width = 72;
  s.height = 56;
  s.camera = scene::frameBounds(m.bounds(), scene::ViewPreset::Iso, double(s.width) / s.height);
  s.transferFunction = scene::makeTransferFunction("viridis");
  s.transferFunction.lo = lo;
  s.transferFunction.hi = hi > lo ? hi : lo + 1;
  s.transferFunction.unitDistance = m.bounds().diagonal() / 8;
  s.dt = scene::defaultStep(scene::elementSizeSum(m).mean(), m.bounds());
  s.integration = Integration::Sampled;  // the grid reference's samples
  s.earlyTermination = 2.0;
  auto gpu = test::renderOnGpu(m, values, s);
  EXPECT_EQ(gpu.validationErrors, 0u) << file;
  EXPECT_EQ(gpu.frame.counters.lostRays, 0u) << file;
  EXPECT_EQ(gpu.frame.counters.stepLimitHits, 0u) << file;
  test::expectImagesClose("shared_" + file, test::renderReference(m, values, s), gpu.image);
}

TEST(SharedData, VtkExampleCells) {
  for (const char* f : {"Tetra.vtu", "Pyramid.vtu", "Wedge.vtu", "Hexahedron.vtu"})
    expectMatchesReference(f);
}
TEST(SharedData, CanHexahedra) {
  expectMatchesReference("can.vtu");
}
TEST(SharedData, NotchWedgesAndHexahedra) {
  expectMatchesReference("notch_stress_fixed.vtk");
}
TEST(SharedData, PostTetrahedra) {
  expectMatchesReference("post.vtk");
}

}  // namespace
}  // namespace sm::render
