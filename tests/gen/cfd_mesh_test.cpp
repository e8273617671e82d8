#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "common/error.h"

#include "gen/generate.h"
#include "gen/mesh_checks.h"
#include "partition/partition.h"

namespace sm::gen {
namespace {

using mesh::CellType;

struct CfdCase {
  const char* name;
  CfdMeshOptions options;
};
void PrintTo(const CfdCase& c, std::ostream* os) {
  *os << c.name;
}

CfdMeshOptions options(Body body, uint64_t target, int clusters, int steps, bool hexBlock) {
  CfdMeshOptions o;
  o.body = body;
  o.targetElements = target;
  o.clusters = clusters;
  o.steps = steps;
  o.hexBlock = hexBlock;
  o.threads = 1;
  return o;
}

// Small meshes only: each takes about a second to generate.
const CfdCase kCases[] = {
    {"CapsuleWithHexBlock", options(Body::Capsule, 15000, 4, 2, true)},
    {"Lander", options(Body::Lander, 20000, 5, 1, false)},
};

class CfdMeshTest : public testing::TestWithParam<CfdCase> {
 protected:
  static const mesh::UnstructuredMesh& meshFor(const CfdCase& c) {
    static std::map<std::string, mesh::UnstructuredMesh> cache;
    auto it = cache.find(c.name);
    if (it == cache.end()) it = cache.emplace(c.name, generateCfdMesh(c.options)).first;
    return it->second;
  }
};

TEST_P(CfdMeshTest, HasThePromisedElementTypesAndCount) {
  const auto& m = meshFor(GetParam());
  const auto& o = GetParam().options;
  EXPECT_GT(m.numCells(CellType::Tet), 0u);
  EXPECT_GT(m.numCells(CellType::Wedge), 0u);
  EXPECT_GT(m.numCells(CellType::Pyramid), 0u);
  if (o.hexBlock) {
    EXPECT_GT(m.numCells(CellType::Hex), 0u);
  }
  const double ratio = double(m.numCells()) / double(o.targetElements);
  EXPECT_GT(ratio, 0.75) << m.numCells() << " elements";
  EXPECT_LT(ratio, 1.25) << m.numCells() << " elements";
}

TEST_P(CfdMeshTest, IsConformingWithValidElements) {
  const auto& m = meshFor(GetParam());
  EXPECT_EQ(m.invertedFixed, 0u) << "gmsh vertex orders were not converted to VTK's";
  auto r = test::matchFaces(m);
  EXPECT_EQ(r.overShared, 0u);
  EXPECT_EQ(r.sameWinding, 0u);
  EXPECT_GT(r.interior, 2 * m.numCells() - r.boundary);
  EXPECT_GT(test::minScaledJacobian(m), 1e-3);

  // The boundary is the far-field box and the body wall, each one closed surface. A face that two
  // elements list with different vertices (a quad against two triangles, a layer face against a
  // tetrahedron) would show up as extra boundary inside the domain.
  const auto b = m.bounds();
  std::vector<test::MeshFace> box, wall;
  for (const auto& f : r.boundaryFaces) {
    bool onBox = false;
    for (int axis = 0; axis < 3; ++axis)
      for (double side : {b.lo[axis], b.hi[axis]}) {
        bool all = true;
        for (int k = 0; k < f.size; ++k) all &= std::abs(m.points[f.ids[k]][axis] - side) < 1e-9;
        onBox |= all;
      }
    (onBox ? box : wall).push_back(f);
  }
  auto boxSurface = test::analyseSurface(box), wallSurface = test::analyseSurface(wall);
  EXPECT_EQ(boxSurface.components, 1);
  EXPECT_TRUE(boxSurface.closedAndOriented);
  EXPECT_EQ(wallSurface.components, 1);
  EXPECT_TRUE(wallSurface.closedAndOriented);
  const glm::dvec3 e = b.extent();
  const double volume = test::totalVolume(m), boxVolume = e.x * e.y * e.z;
  EXPECT_LT(volume, boxVolume - 2.0) << "the body (volume > 2) is a hole in the box";
  EXPECT_GT(volume, boxVolume - 8.0);
}

TEST_P(CfdMeshTest, HasNonEmptyClustersAndFiniteFields) {
  const auto& m = meshFor(GetParam());
  const auto& o = GetParam().options;
  auto sizes = partition::clusterSizes(m);
  ASSERT_EQ(int(sizes.size()), o.clusters);
  for (uint64_t s : sizes) EXPECT_GT(s, 0u);
  for (const char* name : {"linear", "shock", "vortex"}) {
    const mesh::Field* f = m.findField(name);
    ASSERT_NE(f, nullptr) << name;
    EXPECT_EQ(f->numSteps(), uint64_t(o.steps));
    for (const auto& step : f->steps)
      for (float v : step) ASSERT_TRUE(std::isfinite(v)) << name;
  }
}

INSTANTIATE_TEST_SUITE_P(Bodies, CfdMeshTest, testing::ValuesIn(kCases),
                         [](const auto& info) { return std::string(info.param.name); });

// With one gmsh thread the whole pipeline is reproducible, so caches, images and benchmarks built
// on a generated mesh are too.
TEST(CfdMesh, IsBitReproducibleWithOneThread) {
  auto o = options(Body::Lander, 12000, 3, 2, true);
  auto a = generateCfdMesh(o), b = generateCfdMesh(o);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.cells, b.cells);
  EXPECT_EQ(a.clusters, b.clusters);
  ASSERT_EQ(a.fields.size(), b.fields.size());
  for (size_t f = 0; f < a.fields.size(); ++f) EXPECT_EQ(a.fields[f].steps, b.fields[f].steps);
}

TEST(CfdMesh, RejectsBadOptions) {
  auto o = options(Body::Capsule, 12000, 0, 1, false);
  EXPECT_THROW(generateCfdMesh(o), Error);
  o = options(Body::Capsule, 10, 1, 1, false);
  EXPECT_THROW(generateCfdMesh(o), Error);
}

}  // namespace
}  // namespace sm::gen
