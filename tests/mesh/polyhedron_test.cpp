// Polyhedra split into tetrahedra on their own vertices (mesh/polyhedron.h): the volume is kept,
// every tetrahedron is proper and positive, faces shared by two cells are cut the same way, and
// what cannot be split on its vertices is refused with the reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <random>
#include <set>

#include <glm/geometric.hpp>

#include "mesh/element_geometry.h"
#include "mesh/polyhedron.h"
#include "mesh/unstructured_mesh.h"

namespace sm::mesh {
namespace {

using Tets = std::vector<std::array<uint32_t, 4>>;

PolyhedronFaces facesOf(const std::vector<std::vector<uint32_t>>& faces) {
  PolyhedronFaces out;
  for (const auto& f : faces) {
    out.ids.insert(out.ids.end(), f.begin(), f.end());
    out.offsets.push_back(uint32_t(out.ids.size()));
  }
  return out;
}

PolyhedronFaces reversed(const PolyhedronFaces& in) {
  PolyhedronFaces out = in;
  for (size_t f = 0; f < in.numFaces(); ++f)
    std::reverse(out.ids.begin() + in.offsets[f], out.ids.begin() + in.offsets[f + 1]);
  return out;
}

// Every tetrahedron positive and proper; returns their total volume.
double checkedVolume(const Tets& tets, const std::vector<glm::dvec3>& points) {
  double sum = 0.0;
  for (const auto& t : tets) {
    const double v = signedVolume(CellType::Tet, t, points);
    EXPECT_GT(v, 1e-9) << t[0] << " " << t[1] << " " << t[2] << " " << t[3];
    sum += v;
  }
  return sum;
}

std::set<std::array<uint32_t, 4>> asSets(Tets tets) {
  std::set<std::array<uint32_t, 4>> out;
  for (auto& t : tets) {
    std::sort(t.begin(), t.end());
    out.insert(t);
  }
  return out;
}

// Triangles of the tetrahedra, by their sorted points (as `key` names them: the identity unless
// given), with how many tetrahedra have each.
std::map<std::array<uint32_t, 3>, int> triangleUses(
    const Tets& tets, const std::function<uint32_t(uint32_t)>& key = {}) {
  std::map<std::array<uint32_t, 3>, int> uses;
  for (const auto& t : tets)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<uint32_t, 3> f;
      for (int v = 0, o = 0; v < 4; ++v)
        if (v != skip) f[size_t(o++)] = key ? key(t[size_t(v)]) : t[size_t(v)];
      std::sort(f.begin(), f.end());
      ++uses[f];
    }
  return uses;
}

// The unit cube's corners in VTK hexahedron order, faces outward.
std::vector<glm::dvec3> cubePoints() {
  return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
}
const std::vector<std::vector<uint32_t>> kCubeFaces = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                       {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

TEST(Polyhedron, CubeSplitsIntoSixTetrahedraOfItsVolume) {
  const auto points = cubePoints();
  Tets tets;
  ASSERT_EQ(tetrahedralize(facesOf(kCubeFaces), points, tets), PolyhedronSplit::Ok);
  EXPECT_EQ(tets.size(), 6u);  // apex (0,0,0): the three faces away from it, two triangles each
  EXPECT_NEAR(checkedVolume(tets, points), 1.0, 1e-12);
  for (const auto& t : tets) EXPECT_EQ(t[3], 0u);
}

TEST(Polyhedron, InwardFacesGiveTheSameTetrahedra) {
  const auto points = cubePoints();
  Tets out, in;
  ASSERT_EQ(tetrahedralize(facesOf(kCubeFaces), points, out), PolyhedronSplit::Ok);
  ASSERT_EQ(tetrahedralize(reversed(facesOf(kCubeFaces)), points, in), PolyhedronSplit::Ok);
  EXPECT_EQ(asSets(out), asSets(in));
  EXPECT_NEAR(checkedVolume(in, points), 1.0, 1e-12);
}

TEST(Polyhedron, HexagonalPrism) {
  std::vector<glm::dvec3> points;
  for (int z = 0; z < 2; ++z)
    for (int k = 0; k < 6; ++k)
      points.push_back({std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 2.0 * z});
  std::vector<std::vector<uint32_t>> faces = {{5, 4, 3, 2, 1, 0}, {6, 7, 8, 9, 10, 11}};
  for (uint32_t k = 0; k < 6; ++k) faces.push_back({k, (k + 1) % 6, 6 + (k + 1) % 6, 6 + k});
  Tets tets;
  ASSERT_EQ(tetrahedralize(facesOf(faces), points, tets), PolyhedronSplit::Ok);
  EXPECT_NEAR(checkedVolume(tets, points), 2.0 * 3.0 * std::sqrt(3.0) / 2.0, 1e-12);
}

// A point halfway along an edge (as where a refined neighbour meets a cell): the two faces on that
// edge list it, and no tetrahedron may be flat because of it, whether the edge is on the apex (the
// cube's first point, the origin) or away from it.
TEST(Polyhedron, PointOnAnEdgeMakesNoFlatTetrahedron) {
  auto points = cubePoints();
  points.push_back({0.5, 0, 0});  // 8: on the edge 0-1
  points.push_back({1, 0.5, 1});  // 9: on the edge 5-6
  const std::vector<std::vector<std::vector<uint32_t>>> cases = {
      {{0, 3, 2, 1, 8}, {4, 5, 6, 7}, {0, 8, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}},
      {{0, 3, 2, 1}, {4, 5, 9, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 9, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}};
  for (const auto& faces : cases) {
    Tets tets;
    ASSERT_EQ(tetrahedralize(facesOf(faces), points, tets), PolyhedronSplit::Ok);
    EXPECT_NEAR(checkedVolume(tets, points), 1.0, 1e-12);
  }
}

// An L-shaped prism: not convex, and its first point (the origin) does not see the faces of the
// reflex corner from inside; the reflex vertex sees them all.
TEST(Polyhedron, NonConvexCellTakesAVertexThatSeesEveryFace) {
  const std::vector<glm::dvec3> base = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},
                                        {2, 1, 0}, {2, 2, 0}, {0, 2, 0}};
  std::vector<glm::dvec3> points = base;
  for (const auto& p : base) points.push_back(p + glm::dvec3(0, 0, 1));
  std::vector<std::vector<uint32_t>> faces = {{5, 4, 3, 2, 1, 0}, {6, 7, 8, 9, 10, 11}};
  for (uint32_t k = 0; k < 6; ++k) faces.push_back({k, (k + 1) % 6, 6 + (k + 1) % 6, 6 + k});
  Tets tets;
  ASSERT_EQ(tetrahedralize(facesOf(faces), points, tets), PolyhedronSplit::Ok);
  EXPECT_NEAR(checkedVolume(tets, points), 3.0, 1e-12);
  EXPECT_NE(tets[0][3], 0u);  // the origin could not be the apex
}

// Schönhardt's twisted prism: no tetrahedralization on its own vertices exists at all.
TEST(Polyhedron, SchoenhardtPrismIsRefused) {
  std::vector<glm::dvec3> points;
  for (int k = 0; k < 3; ++k)
    points.push_back({std::cos(k * 2 * M_PI / 3), std::sin(k * 2 * M_PI / 3), 0});
  for (int k = 0; k < 3; ++k) {
    const double a = k * 2 * M_PI / 3 + 0.5;  // twisted by about 29 degrees
    points.push_back({std::cos(a), std::sin(a), 1});
  }
  // Bottom, top, and each side quad cut along its reflex diagonal (k, k + 1 on top).
  std::vector<std::vector<uint32_t>> faces = {{0, 2, 1}, {3, 4, 5}};
  for (uint32_t k = 0; k < 3; ++k) {
    const uint32_t k1 = (k + 1) % 3;
    faces.push_back({k, k1, 3 + k1});
    faces.push_back({k, 3 + k1, 3 + k});
  }
  // Which diagonal is reflex depends on the twist's sense: try both ways of cutting, one of which
  // is the twisted (non-convex) prism; its convex twin splits.
  std::vector<std::vector<uint32_t>> other = {{0, 2, 1}, {3, 4, 5}};
  for (uint32_t k = 0; k < 3; ++k) {
    const uint32_t k1 = (k + 1) % 3;
    other.push_back({k, k1, 3 + k});
    other.push_back({k1, 3 + k1, 3 + k});
  }
  Tets a, b;
  const PolyhedronSplit sa = tetrahedralize(facesOf(faces), points, a);
  const PolyhedronSplit sb = tetrahedralize(facesOf(other), points, b);
  EXPECT_TRUE((sa == PolyhedronSplit::NotStarShaped) != (sb == PolyhedronSplit::NotStarShaped))
      << describe(sa) << " / " << describe(sb);
  EXPECT_TRUE(sa == PolyhedronSplit::Ok || sb == PolyhedronSplit::Ok);
  EXPECT_TRUE(sa == PolyhedronSplit::Ok ? b.empty() : a.empty());  // refused: nothing appended
}

// A prism on a regular k-gon: a fan splits any size of convex face; past kMaxFacePoints the cell
// is refused before any work that grows with it.
std::vector<std::vector<uint32_t>> prism(uint32_t k, std::vector<glm::dvec3>& points) {
  points.clear();
  for (int z = 0; z < 2; ++z)
    for (uint32_t i = 0; i < k; ++i)
      points.push_back({std::cos(2 * M_PI * i / k), std::sin(2 * M_PI * i / k), double(z)});
  std::vector<std::vector<uint32_t>> faces(2);
  for (uint32_t i = 0; i < k; ++i) {
    faces[0].push_back(k - 1 - i);
    faces[1].push_back(k + i);
    faces.push_back({i, (i + 1) % k, k + (i + 1) % k, k + i});
  }
  return faces;
}

TEST(Polyhedron, LargeCellsAreBounded) {
  std::vector<glm::dvec3> points;
  Tets tets;
  auto faces = prism(200, points);
  ASSERT_EQ(tetrahedralize(facesOf(faces), points, tets), PolyhedronSplit::Ok);
  EXPECT_NEAR(checkedVolume(tets, points), 100 * std::sin(2 * M_PI / 200), 1e-9);
  faces = prism(kMaxFacePoints + 1, points);
  EXPECT_EQ(tetrahedralize(facesOf(faces), points, tets), PolyhedronSplit::TooLarge);
}

TEST(Polyhedron, OpenOrMisorientedSurfacesAreRefused) {
  const auto points = cubePoints();
  Tets tets;
  auto open = kCubeFaces;
  open.pop_back();
  EXPECT_EQ(tetrahedralize(facesOf(open), points, tets), PolyhedronSplit::NotClosed);
  auto flipped = kCubeFaces;
  std::reverse(flipped[2].begin(), flipped[2].end());
  EXPECT_EQ(tetrahedralize(facesOf(flipped), points, tets), PolyhedronSplit::NotClosed);
  EXPECT_TRUE(tets.empty());
  // A flat "polyhedron": closed, but no vertex sees a face with any volume.
  auto flat = points;
  for (auto& p : flat) p.z = 0;
  EXPECT_NE(tetrahedralize(facesOf(kCubeFaces), flat, tets), PolyhedronSplit::Ok);
}

TEST(Polyhedron, FaceTriangulationIgnoresOrientationAndStart) {
  const std::vector<glm::dvec3> points = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0},
                                          {1, 3, 0}, {0, 2, 0}, {1, 0, 0}};
  const std::vector<uint32_t> cycle = {0, 5, 1, 2, 3, 4};  // 5 on the edge 0-1
  std::set<std::array<uint32_t, 3>> first;
  for (int rot = 0; rot < 6; ++rot) {
    for (bool flip : {false, true}) {
      std::vector<uint32_t> c = cycle;
      std::rotate(c.begin(), c.begin() + rot, c.end());
      if (flip) std::reverse(c.begin(), c.end());
      std::vector<std::array<uint32_t, 3>> tris;
      ASSERT_TRUE(triangulateFace(c, points, tris));
      ASSERT_EQ(tris.size(), 4u);
      double area = 0;
      std::set<std::array<uint32_t, 3>> sets;
      for (auto t : tris) {
        const glm::dvec3 n = glm::cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]);
        EXPECT_GT(std::abs(n.z), 1e-9) << "a flat triangle";
        EXPECT_EQ(n.z > 0, !flip) << "turns against the face";
        area += std::abs(n.z) / 2;
        std::sort(t.begin(), t.end());
        sets.insert(t);
      }
      EXPECT_NEAR(area, 5.0, 1e-12);
      if (first.empty()) first = sets;
      EXPECT_EQ(sets, first);
    }
  }
  std::vector<std::array<uint32_t, 3>> tris;
  EXPECT_FALSE(triangulateFace(std::vector<uint32_t>{0, 5, 1}, points, tris));  // collinear
  EXPECT_FALSE(triangulateFace(std::vector<uint32_t>{0, 1, 0, 2}, points, tris));
  EXPECT_TRUE(tris.empty());
}

// A 3x3x3 block of cubes, each a polyhedron, under a random numbering of the points: every
// triangle between two cells is a face of a tetrahedron on each side (a conforming split), and
// only the block's outside has triangles of one cell alone.
TEST(Polyhedron, NeighboursCutSharedFacesTheSameWay) {
  const int n = 3;
  std::vector<uint32_t> id((n + 1) * (n + 1) * (n + 1));
  std::iota(id.begin(), id.end(), 0u);
  std::shuffle(id.begin(), id.end(), std::mt19937(7));
  std::vector<glm::dvec3> points(id.size());
  auto at = [&](int i, int j, int k) { return id[size_t((k * (n + 1) + j) * (n + 1) + i)]; };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) points[at(i, j, k)] = glm::dvec3(i, j, k);
  Tets all;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        std::vector<std::vector<uint32_t>> faces;
        const uint32_t c[8] = {
            at(i, j, k),     at(i + 1, j, k),     at(i + 1, j + 1, k),     at(i, j + 1, k),
            at(i, j, k + 1), at(i + 1, j, k + 1), at(i + 1, j + 1, k + 1), at(i, j + 1, k + 1)};
        for (const auto& f : kCubeFaces) faces.push_back({c[f[0]], c[f[1]], c[f[2]], c[f[3]]});
        ASSERT_EQ(tetrahedralize(facesOf(faces), points, all), PolyhedronSplit::Ok);
      }
  EXPECT_NEAR(checkedVolume(all, points), n * n * n, 1e-9);
  for (const auto& [f, count] : triangleUses(all)) {
    EXPECT_LE(count, 2);
    if (count == 1) {  // on the outside: all three points on one side of the block
      bool outside = false;
      for (int axis = 0; axis < 3; ++axis)
        for (double side : {0.0, double(n)})
          outside = outside || (points[f[0]][axis] == side && points[f[1]][axis] == side &&
                                points[f[2]][axis] == side);
      EXPECT_TRUE(outside) << "an inner triangle of one cell only: the split does not conform";
    }
  }
}

// The same block as if every cell came from a piece of its own (a .pvtu before the weld): each
// numbers its eight points afresh, in a random order, so that only positions say which points are
// the same. After mapping the copies back to one point per position, the split still conforms.
TEST(Polyhedron, PiecesNumberingSharedPointsDifferentlyStillConform) {
  const int n = 2;
  std::vector<glm::dvec3> points;
  std::mt19937 rng(3);
  Tets all;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const auto corners = cubePoints();
        std::vector<uint32_t> id(8);
        std::iota(id.begin(), id.end(), uint32_t(points.size()));
        std::shuffle(id.begin(), id.end(), rng);
        points.resize(points.size() + 8);
        for (int v = 0; v < 8; ++v)
          points[id[size_t(v)]] = corners[size_t(v)] + glm::dvec3(i, j, k);
        std::vector<std::vector<uint32_t>> faces;
        for (const auto& f : kCubeFaces) faces.push_back({id[f[0]], id[f[1]], id[f[2]], id[f[3]]});
        ASSERT_EQ(tetrahedralize(facesOf(faces), points, all), PolyhedronSplit::Ok);
      }
  auto key = [&](uint32_t v) {
    const glm::dvec3 p = points[v];
    return uint32_t((p.z * (n + 1) + p.y) * (n + 1) + p.x);
  };
  size_t once = 0;
  for (const auto& [f, count] : triangleUses(all, key)) {
    EXPECT_LE(count, 2);
    once += count == 1 ? 1 : 0;
  }
  EXPECT_EQ(once, size_t(6 * n * n * 2));  // the outside's squares, two triangles each
}

// Non-finite values counted by cells: consecutive elements of one origin (a polyhedron's
// tetrahedra) once, elements without origins each.
TEST(NonFiniteCells, APolyhedronsTetrahedraCountOnce) {
  const float nan = std::nanf("");
  const std::vector<float> values = {1, nan, nan, nan, 2, nan, nan};
  const std::vector<uint32_t> origins = {0, 1, 1, 1, 2, 3, 4};
  EXPECT_EQ(nonFiniteCells(values, origins), 3u);  // cells 1, 3 and 4
  EXPECT_EQ(nonFiniteCells(values, {}), 5u);
}

// Each face of `cell` turned outward (Newell normal away from the cell's centre): the cells below
// are convex enough for that.
PolyhedronFaces outward(std::vector<std::vector<uint32_t>> cell, const std::vector<glm::dvec3>& p) {
  glm::dvec3 centre(0.0);
  size_t n = 0;
  for (const auto& f : cell)
    for (uint32_t v : f) centre += p[v], ++n;
  centre /= double(n);
  for (auto& f : cell) {
    glm::dvec3 normal(0.0), mid(0.0);
    for (size_t i = 0; i < f.size(); ++i) {
      normal += glm::cross(p[f[i]], p[f[(i + 1) % f.size()]]);
      mid += p[f[i]];
    }
    if (glm::dot(normal, mid / double(f.size()) - centre) < 0.0) std::reverse(f.begin(), f.end());
  }
  return facesOf(cell);
}

// A warped face between two cells where one of them cannot take the face's first point as its
// apex: cell C (x from 0 to 1) has its bottom cut in two by hanging points in the middle of two
// edges (octree refinement), so the corner p = (0,0,0) lies in the plane of the bottom's far half
// and another vertex must be the apex; the face F at x = 0 is warped (its corner (0,1,0) moved to
// x = 0.05). Both cells must still cut F the same way, or the warp leaves a gap or an overlap: F's
// triangles are faces of a tetrahedron on each side. (They were not when a later apex covered
// the faces it is on by its own fan.) A face whose fan has a sliver triangle, which its own cut
// avoids, likewise.
TEST(Polyhedron, AWarpedFaceIsCutAlikeWhateverTheApex) {
  const std::vector<glm::dvec3> points = {
      {0, 0, 0}, {0, 0, 1},   {0, 1, 1},   {0.05, 1, 0}, {1, 0, 0},  {1, 1, 0},  {1, 0, 1},
      {1, 1, 1}, {0.5, 0, 0}, {0.5, 1, 0}, {-1, 0, 0},   {-1, 1, 0}, {-1, 0, 1}, {-1, 1, 1}};
  enum : uint32_t { p, t0, t3, c, a, b, t1, t2, m1, m2, n0, n1, n2, n3 };
  const PolyhedronFaces cellC = outward({{p, c, m2, m1},
                                         {m1, m2, b, a},
                                         {p, m1, a, t1, t0},
                                         {c, t3, t2, b, m2},
                                         {t0, t1, t2, t3},
                                         {a, b, t2, t1},
                                         {p, t0, t3, c}},
                                        points);
  const PolyhedronFaces cellN = outward({{p, t0, t3, c},
                                         {n0, n2, n3, n1},
                                         {n0, p, c, n1},
                                         {n2, n3, t3, t0},
                                         {n0, n2, t0, p},
                                         {n1, c, t3, n3}},
                                        points);
  for (bool flip : {false, true}) {
    SCOPED_TRACE(flip ? "inward faces" : "outward faces");
    Tets tc, tn;
    ASSERT_EQ(tetrahedralize(flip ? reversed(cellC) : cellC, points, tc), PolyhedronSplit::Ok);
    ASSERT_EQ(tetrahedralize(flip ? reversed(cellN) : cellN, points, tn), PolyhedronSplit::Ok);
    EXPECT_TRUE(std::none_of(tc.begin(), tc.end(), [](const auto& t) { return t[3] == p; }))
        << "the case needs an apex other than the face's first point";
    Tets both = tc;
    both.insert(both.end(), tn.begin(), tn.end());
    // C is the unit cube with a corner moved by 0.05 along x, N the unit cube with one moved the
    // other way: their volumes sum to 2.
    EXPECT_NEAR(checkedVolume(both, points), 2.0, 1e-12);
    const std::set<uint32_t> onF = {p, t0, t3, c};
    int faceTriangles = 0;
    for (const auto& [f, count] : triangleUses(both)) {
      EXPECT_LE(count, 2);
      if (onF.count(f[0]) && onF.count(f[1]) && onF.count(f[2])) {
        ++faceTriangles;
        EXPECT_EQ(count, 2) << "F cut differently by the two cells: " << f[0] << " " << f[1] << " "
                            << f[2];
      }
    }
    EXPECT_GE(faceTriangles, 2);  // F's two, and the faces of a sliver on the warp
  }
}

// A warped quad whose fan from its first point has a sliver in the face's plane (a point 1e-10 off
// the line of its neighbours) is ear-clipped as a face; the prisms on both sides of it, one with
// that point as its apex, must still cut it alike, or the warp leaves a gap or an overlap. (Flat,
// the two cuts would cover the same plane: touching shells, which traversal handles.)
TEST(Polyhedron, AWarpedFaceWithASliverFanIsCutAlikeOnBothSides) {
  for (double warp : {0.01, -0.01}) {
    SCOPED_TRACE(warp);
    std::vector<glm::dvec3> points = {{0, 0, 0}, {1, 0, 0}, {2, 1e-10, warp}, {0, 1, 0}};
    for (double z : {1.0, -1.0})
      for (int i = 0; i < 4; ++i)
        points.push_back(points[size_t(i)] * glm::dvec3(1, 1, 0) + glm::dvec3(0, 0, z));
    Tets both;
    for (uint32_t o : {4u, 8u}) {  // the prism above F, then the one below
      const PolyhedronFaces prism = outward({{0, 1, 2, 3},
                                             {o, o + 1, o + 2, o + 3},
                                             {0, 1, o + 1, o},
                                             {1, 2, o + 2, o + 1},
                                             {2, 3, o + 3, o + 2},
                                             {3, 0, o, o + 3}},
                                            points);
      ASSERT_EQ(tetrahedralize(prism, points, both), PolyhedronSplit::Ok);
    }
    // Two unit prisms (F's area is 1 + 5e-11; what the warp takes from one it gives the other),
    // every tetrahedron positive, the slivers along the nearly flat sides too.
    double volume = 0.0;
    for (const auto& t : both) {
      const double v = signedVolume(CellType::Tet, t, points);
      EXPECT_GT(v, 0.0);
      volume += v;
    }
    EXPECT_NEAR(volume, 2.0, 1e-9);
    const std::set<uint32_t> onF = {0, 1, 2, 3};
    for (const auto& [f, count] : triangleUses(both)) {
      if (onF.count(f[0]) && onF.count(f[1]) && onF.count(f[2])) {
        EXPECT_EQ(count, 2) << "F cut differently: " << f[0] << " " << f[1] << " " << f[2];
      }
    }
  }
}

}  // namespace
}  // namespace sm::mesh
