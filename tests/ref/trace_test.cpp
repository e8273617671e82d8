// traceRay: known intervals on single elements, and watertightness on a cube split five ways:
// random rays and axis-aligned rays through vertices, along edges and in face planes must give
// the ray-box slab interval as a gap-free, overlap-free chain of crossings.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "ref/reference_renderer.h"
#include "test_meshes.h"

namespace sm::ref {
namespace {

using mesh::CellType;
using test::Split;

TEST(TraceRay, SingleTetKnownAnswer) {
  auto m = test::singleElement(CellType::Tet, test::referenceCorners(CellType::Tet));
  ReferenceRenderer r(m);
  auto up = r.traceRay({0.125, 0.25, -1.0}, {0, 0, 1});
  ASSERT_EQ(up.size(), 1u);
  EXPECT_EQ(up[0].tIn, 1.0);
  EXPECT_EQ(up[0].tOut, 1.625);
  EXPECT_EQ(up[0].type, CellType::Tet);
  EXPECT_EQ(up[0].index, 0u);
  auto down = r.traceRay({0.125, 0.25, 2.0}, {0, 0, -2});  // t in units of |dir|
  ASSERT_EQ(down.size(), 1u);
  EXPECT_EQ(down[0].tIn, 0.6875);
  EXPECT_EQ(down[0].tOut, 1.0);
  EXPECT_TRUE(r.traceRay({0.125, 0.25, 2.0}, {0, 0, 1}).empty());  // pointing away
  auto inside = r.traceRay({0.125, 0.25, 0.5}, {0, 0, 1});         // origin inside
  ASSERT_EQ(inside.size(), 1u);
  EXPECT_EQ(inside[0].tIn, 0.0);
  EXPECT_EQ(inside[0].tOut, 0.125);
}

TEST(TraceRay, GrazingInvertedAndFlatElementsGiveNothing) {
  auto corners = test::referenceCorners(CellType::Tet);
  auto tet = test::singleElement(CellType::Tet, corners);
  ReferenceRenderer r(tet);
  // Through the apex only, and through the apex along an edge direction from outside.
  EXPECT_TRUE(r.traceRay({-1, -1, 1}, {1, 1, 0}).empty());
  auto edge = r.traceRay({0, -1, 2}, {0, 1, -1});  // along the edge from the apex to (0, 1, 0)
  ASSERT_LE(edge.size(), 1u);
  if (!edge.empty()) {
    EXPECT_NEAR(edge[0].tOut - edge[0].tIn, 1.0, 1e-12);
  }
  auto mirrored = corners;
  std::swap(mirrored[1], mirrored[2]);  // faces wound inward
  auto inverted = test::singleElement(CellType::Tet, mirrored);
  ReferenceRenderer ri(inverted);
  auto flat = test::singleElement(CellType::Tet, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}});
  ReferenceRenderer rf(flat);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    glm::dvec3 target(0.5 * u(rng) + 0.25, 0.5 * u(rng) + 0.25, 0.5 * u(rng) + 0.25);
    glm::dvec3 origin = target + 3.0 * glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
    EXPECT_TRUE(ri.traceRay(origin, target - origin).empty());
    // A flat element's entries and exits lie in one plane: at most rounding-level slivers.
    for (const Crossing& c : rf.traceRay(origin, target - origin))
      EXPECT_LT(c.tOut - c.tIn, 1e-14 * c.tOut);
  }
}

// Checks that the crossings chain from the box entry to the box exit without gaps or overlaps
// (each within `gap`), or are empty when the ray misses; returns whether any crossing was found.
bool expectChain(const std::vector<Crossing>& cs, const Interval& box, double gap,
                 const std::string& what, double ends = 1e-12) {
  if (box.tIn >= box.tOut) {
    EXPECT_TRUE(cs.empty()) << what;
    return false;
  }
  if (cs.empty()) {
    ADD_FAILURE() << what << ": no crossing for a box interval of length " << box.tOut - box.tIn;
    return false;
  }
  EXPECT_NEAR(cs.front().tIn, box.tIn, ends) << what;
  EXPECT_NEAR(cs.back().tOut, box.tOut, ends) << what;
  double length = 0.0;
  for (size_t i = 0; i < cs.size(); ++i) {
    EXPECT_TRUE(std::isfinite(cs[i].tIn) && std::isfinite(cs[i].tOut)) << what;
    EXPECT_LT(cs[i].tIn, cs[i].tOut) << what;
    length += cs[i].tOut - cs[i].tIn;
    if (i > 0) {
      EXPECT_NEAR(cs[i].tIn, cs[i - 1].tOut, gap) << what << " crossing " << i;
    }
  }
  EXPECT_NEAR(length, box.tOut - box.tIn, ends) << what;
  return true;
}

TEST(TraceRay, RandomRaysThroughCubeSplitsChainExactly) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.3, 1.3), dir(-1.0, 1.0);
  for (Split split : test::kAllSplits) {
    for (int n = 1; n <= 3; ++n) {
      auto m = test::cubeMesh(split, n);
      ReferenceRenderer r(m);
      int hits = 0;
      for (int i = 0; i < 300; ++i) {
        glm::dvec3 target(u(rng), u(rng), u(rng));
        glm::dvec3 origin =
            glm::dvec3(0.5) + 2.5 * glm::normalize(glm::dvec3(dir(rng), dir(rng), dir(rng)));
        glm::dvec3 d = target - origin;
        std::string what = test::splitName(split) + " n=" + std::to_string(n);
        // Conforming faces are evaluated identically from both sides: touching is exact.
        hits += expectChain(r.traceRay(origin, d),
                            test::slab(glm::dvec3(0), glm::dvec3(1), origin, d), 0.0, what);
      }
      EXPECT_GT(hits, 100);
    }
  }
}

// Small elements far from the origin: the chain stays exact; the ends agree with the slab test
// to the rounding of coordinates near 1e6 (ulp 1.2e-10).
TEST(TraceRay, SmallElementsFarFromTheOrigin) {
  const glm::dvec3 lo(1e6, -1e6, 5e5);
  const double size = 0.01;
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-0.2, 1.2), dir(-1.0, 1.0);
  for (Split split : test::kAllSplits) {
    auto m = test::cubeMesh(split, 2, size, lo);
    ReferenceRenderer r(m);
    const glm::dvec3 boxLo = m.points.front(), boxHi = m.points[(3 * 3 * 3) - 1];
    int hits = 0;
    for (int i = 0; i < 200; ++i) {
      glm::dvec3 target = lo + size * glm::dvec3(u(rng), u(rng), u(rng));
      glm::dvec3 origin =
          lo +
          size * (glm::dvec3(0.5) + 3.0 * glm::normalize(glm::dvec3(dir(rng), dir(rng), dir(rng))));
      glm::dvec3 d = glm::normalize(target - origin);
      hits += expectChain(r.traceRay(origin, d), test::slab(boxLo, boxHi, origin, d), 0.0,
                          test::splitName(split), 1e-9);
    }
    EXPECT_GT(hits, 50);
  }
}

TEST(TraceRay, CameraInsideStartsAtZero) {
  for (Split split : test::kAllSplits) {
    auto m = test::cubeMesh(split, 2);
    ReferenceRenderer r(m);
    glm::dvec3 origin(0.3, 0.4, 0.6), d(0.2, -0.5, 0.7);
    auto cs = r.traceRay(origin, d);
    ASSERT_FALSE(cs.empty());
    EXPECT_EQ(cs.front().tIn, 0.0);
    expectChain(cs, test::slab(glm::dvec3(0), glm::dvec3(1), origin, d), 0.0,
                test::splitName(split));
  }
}

// Axis-aligned rays on the lines where the other two coordinates are multiples of 1/4, in a cube
// of 2^3 cells: through vertices, along edges, in the planes of internal faces.
TEST(TraceRay, AxisAlignedRaysThroughVerticesAndEdges) {
  const double coords[5] = {0.0, 0.25, 0.5, 0.75, 1.0};
  std::vector<std::vector<bool>> boundaryHits(test::kAllSplits.size());
  for (size_t s = 0; s < test::kAllSplits.size(); ++s) {
    auto m = test::cubeMesh(test::kAllSplits[s], 2);
    ReferenceRenderer r(m);
    for (int axis = 0; axis < 3; ++axis)
      for (double sign : {1.0, -1.0})
        for (double a : coords)
          for (double b : coords) {
            glm::dvec3 origin(0.0), d(0.0);
            origin[axis] = sign > 0 ? -0.5 : 1.5;
            origin[(axis + 1) % 3] = a;
            origin[(axis + 2) % 3] = b;
            d[axis] = sign;
            auto cs = r.traceRay(origin, d);
            std::string what = test::splitName(test::kAllSplits[s]) + " axis " +
                               std::to_string(axis) + " at " + std::to_string(a) + "," +
                               std::to_string(b);
            bool boundary = a == 0.0 || a == 1.0 || b == 0.0 || b == 1.0;
            if (!boundary) {
              // The perturbed ray may cross a zero-length element at a vertex: touching to 1e-12.
              expectChain(cs, {0.5, 1.5}, 1e-12, what);
            } else {
              // In the cube's surface: inside or outside for every split alike, never partly.
              if (!cs.empty()) expectChain(cs, {0.5, 1.5}, 1e-12, what);
              boundaryHits[s].push_back(!cs.empty());
            }
          }
  }
  for (size_t s = 1; s < boundaryHits.size(); ++s)
    EXPECT_EQ(boundaryHits[s], boundaryHits[0]) << test::splitName(test::kAllSplits[s]);
}

// A hexahedron with a warped top face is the union of the cones from its centre over its
// boundary triangles; random rays must see the same total length through both.
TEST(TraceRay, WarpedHexEqualsItsBoundaryCones) {
  auto corners = test::referenceCorners(CellType::Hex);
  corners[6].z = 1.35;  // top face no longer planar
  corners[4].z = 1.2;
  auto warped = test::singleElement(CellType::Hex, corners);
  ReferenceRenderer hex(warped);
  mesh::UnstructuredMesh cones;
  cones.points = corners;
  glm::dvec3 centre(0.0);
  for (const auto& c : corners) centre += c / 8.0;
  cones.points.push_back(centre);
  const std::vector<uint32_t> ids = {0, 1, 2, 3, 4, 5, 6, 7};
  auto& tets = cones.cells[mesh::typeIndex(CellType::Tet)];
  for (uint32_t f = 0; f < 6; ++f) {
    uint32_t t[6], other[2];
    gpu::smQuadSplit(mesh::faceVert(CellType::Hex, f, 0), mesh::faceVert(CellType::Hex, f, 1),
                     mesh::faceVert(CellType::Hex, f, 2), mesh::faceVert(CellType::Hex, f, 3), t,
                     other);
    // For an outward boundary triangle (a, b, c), the cone (a, c, b, centre) is positive.
    for (int k = 0; k < 6; k += 3) tets.insert(tets.end(), {t[k], t[k + 2], t[k + 1], 8u});
  }
  cones.clusters[mesh::typeIndex(CellType::Tet)].assign(12, 0);
  ReferenceRenderer cone(cones);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-0.2, 1.2), dir(-1.0, 1.0);
  auto total = [](const std::vector<Crossing>& cs) {
    double sum = 0.0;
    for (const auto& c : cs) sum += c.tOut - c.tIn;
    return sum;
  };
  for (int i = 0; i < 500; ++i) {
    glm::dvec3 target(u(rng), u(rng), u(rng) * 1.2);
    glm::dvec3 origin = target + 3.0 * glm::normalize(glm::dvec3(dir(rng), dir(rng), dir(rng)));
    EXPECT_NEAR(total(hex.traceRay(origin, target - origin)),
                total(cone.traceRay(origin, target - origin)), 1e-12);
  }
}

}  // namespace
}  // namespace sm::ref
