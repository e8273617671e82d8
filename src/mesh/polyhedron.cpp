#include "mesh/polyhedron.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace sm::mesh {
namespace {

// Relative to the face's own size (|normal|^2, four times its squared area): below this a triangle
// has no area to speak of, such as three points on one straight edge.
constexpr double kFlatTriangle = 1e-10;
// Relative to the cube of the polyhedron's diagonal: below this a tetrahedron has no volume.
constexpr double kFlatTet = 1e-12;

// The face's normal by Newell's method (twice its vector area): sound for non-planar faces too.
glm::dvec3 newellNormal(std::span<const uint32_t> cycle, const std::vector<glm::dvec3>& p) {
  glm::dvec3 n(0.0);
  for (size_t i = 0; i < cycle.size(); ++i) {
    const glm::dvec3& a = p[cycle[i]];
    const glm::dvec3& b = p[cycle[(i + 1) % cycle.size()]];
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  return n;
}

// The order that picks apexes and where a face's triangulation starts: by position (x, then y,
// then z), ties by id. Positions, not ids, so that the pieces of a partitioned file, which number
// a shared point differently, still cut a shared face the same way.
bool before(uint32_t a, uint32_t b, const std::vector<glm::dvec3>& p) {
  const glm::dvec3 &u = p[a], &v = p[b];
  if (u.x != v.x) return u.x < v.x;
  if (u.y != v.y) return u.y < v.y;
  if (u.z != v.z) return u.z < v.z;
  return a < b;
}

// Positive when a, b, c turn the way normal n says (twice the area projected along n, times |n|).
double turn(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& n) {
  return glm::dot(glm::cross(b - a, c - a), n);
}

// Ear clipping of `seq` (turning as n says): the first proper ear in sequence order each time, so
// that the result depends on the sequence alone. A point on the new diagonal counts as inside,
// which keeps hanging points from becoming T-junctions.
bool clipEars(std::vector<uint32_t> seq, const std::vector<glm::dvec3>& p, const glm::dvec3& n,
              double flat, std::vector<std::array<uint32_t, 3>>& out) {
  while (seq.size() > 3) {
    const size_t k = seq.size();
    bool clipped = false;
    for (size_t i = 0; i < k && !clipped; ++i) {
      const uint32_t a = seq[(i + k - 1) % k], b = seq[i], c = seq[(i + 1) % k];
      if (turn(p[a], p[b], p[c], n) <= flat) continue;
      bool empty = true;
      for (uint32_t v : seq) {
        if (v == a || v == b || v == c) continue;
        if (turn(p[a], p[b], p[v], n) >= 0 && turn(p[b], p[c], p[v], n) >= 0 &&
            turn(p[c], p[a], p[v], n) >= 0) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      out.push_back({a, b, c});
      seq.erase(seq.begin() + std::ptrdiff_t(i));
      clipped = true;
    }
    if (!clipped) return false;
  }
  if (turn(p[seq[0]], p[seq[1]], p[seq[2]], n) <= flat) return false;
  out.push_back({seq[0], seq[1], seq[2]});
  return true;
}

// Every directed edge of the faces once, and its reverse once: a closed surface whose faces all
// turn the same way.
bool closedAndOriented(const PolyhedronFaces& faces) {
  std::vector<uint64_t> edges;
  edges.reserve(faces.ids.size());
  for (size_t f = 0; f < faces.numFaces(); ++f) {
    std::span<const uint32_t> c = faces.face(f);
    for (size_t i = 0; i < c.size(); ++i)
      edges.push_back(uint64_t(c[i]) << 32 | c[(i + 1) % c.size()]);
  }
  std::sort(edges.begin(), edges.end());
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
  for (uint64_t e : edges)
    if (!std::binary_search(edges.begin(), edges.end(), (e << 32) | (e >> 32))) return false;
  return true;
}

}  // namespace

const char* describe(PolyhedronSplit s) {
  switch (s) {
    case PolyhedronSplit::Ok:
      return "split";
    case PolyhedronSplit::NotClosed:
      return "its faces do not close, or do not all turn the same way";
    case PolyhedronSplit::NotStarShaped:
      return "none of its vertices sees all its other faces from inside";
    case PolyhedronSplit::BadFace:
      return "a face is degenerate";
    case PolyhedronSplit::TooLarge:
      return "more than 1024 faces, or a face of more than 256 points";
  }
  return "?";
}

bool triangulateFace(std::span<const uint32_t> cycle, const std::vector<glm::dvec3>& points,
                     std::vector<std::array<uint32_t, 3>>& tris) {
  const size_t n = cycle.size();
  if (n < 3) return false;
  // Read from the first point (in `before` order) towards the earlier of its neighbours: both
  // cells on a face agree on that.
  auto less = [&](uint32_t a, uint32_t b) { return before(a, b, points); };
  const size_t m = size_t(std::min_element(cycle.begin(), cycle.end(), less) - cycle.begin());
  const bool forward = less(cycle[(m + 1) % n], cycle[(m + n - 1) % n]);
  std::vector<uint32_t> seq(n);
  for (size_t i = 0; i < n; ++i) seq[i] = cycle[forward ? (m + i) % n : (m + n - i) % n];
  for (size_t i = 1; i < n; ++i)
    if (seq[i] == seq[0] ||
        std::find(seq.begin() + std::ptrdiff_t(i) + 1, seq.end(), seq[i]) != seq.end())
      return false;  // a point twice
  const glm::dvec3 normal = newellNormal(seq, points);
  const double flat = kFlatTriangle * glm::dot(normal, normal);
  if (!(flat > 0.0)) return false;  // no area (or not finite)
  const size_t first = tris.size();
  bool fan = true;
  for (size_t i = 1; i + 1 < n && fan; ++i)
    fan = turn(points[seq[0]], points[seq[i]], points[seq[i + 1]], normal) > flat;
  if (fan) {
    for (size_t i = 1; i + 1 < n; ++i) tris.push_back({seq[0], seq[i], seq[i + 1]});
  } else if (n > kMaxEarClipPoints || !clipEars(seq, points, normal, flat, tris)) {
    tris.resize(first);
    return false;
  }
  if (!forward)  // back to the face's own orientation
    for (size_t t = first; t < tris.size(); ++t) std::swap(tris[t][1], tris[t][2]);
  return true;
}

PolyhedronSplit tetrahedralize(const PolyhedronFaces& faces, const std::vector<glm::dvec3>& points,
                               std::vector<std::array<uint32_t, 4>>& tets) {
  if (faces.numFaces() > kMaxPolyhedronFaces) return PolyhedronSplit::TooLarge;
  for (size_t f = 0; f < faces.numFaces(); ++f)
    if (faces.face(f).size() > kMaxFacePoints) return PolyhedronSplit::TooLarge;
  if (faces.numFaces() < 4 || !closedAndOriented(faces)) return PolyhedronSplit::NotClosed;
  std::vector<std::array<uint32_t, 3>> tris;
  std::vector<size_t> faceEnd;  // tris of face f: [faceEnd[f - 1], faceEnd[f])
  for (size_t f = 0; f < faces.numFaces(); ++f) {
    if (!triangulateFace(faces.face(f), points, tris)) return PolyhedronSplit::BadFace;
    faceEnd.push_back(tris.size());
  }
  std::vector<uint32_t> verts = faces.ids;
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  std::sort(verts.begin(), verts.end(),
            [&](uint32_t a, uint32_t b) { return before(a, b, points); });
  glm::dvec3 lo = points[verts[0]], hi = lo;
  for (uint32_t v : verts) {
    lo = glm::min(lo, points[v]);
    hi = glm::max(hi, points[v]);
  }
  const double size = glm::length(hi - lo), flat = kFlatTet * size * size * size;
  // In `before` order, so that the first point is the apex wherever it can be (header comment).
  if (verts.size() > kMaxApexTries) verts.resize(kMaxApexTries);
  // The cone over boundary triangle t from the apex: +1 or -1 by its orientation; 0 for a
  // triangle holding the apex; kFlatOnApexFace for one of a face on the apex that is flat with it
  // (no tetrahedron there: the cones over the other faces end on the apex's fan instead, the
  // face's own cut only if that is a fan from the apex); kFlatElsewhere where the apex cannot be
  // used (flat with a face it is not on).
  constexpr int kFlatOnApexFace = 3, kFlatElsewhere = 2;
  auto cone = [&](uint32_t apex, size_t t, bool apexFace) {
    const auto& r = tris[t];
    if (apexFace && (r[0] == apex || r[1] == apex || r[2] == apex)) return 0;
    const glm::dvec3& a = points[r[0]];
    const double v = glm::dot(glm::cross(points[r[1]] - a, points[r[2]] - a), points[apex] - a);
    return v > flat ? 1 : v < -flat ? -1 : apexFace ? kFlatOnApexFace : kFlatElsewhere;
  };
  auto onFace = [&](size_t f, uint32_t apex) {
    std::span<const uint32_t> c = faces.face(f);
    return std::find(c.begin(), c.end(), apex) != c.end();
  };
  // The sign of every cone from `apex` (0 if it cannot be the apex), and whether it is exact:
  // no face on it is flat with it unless that face is a fan from it. Every face keeps its own cut
  // (triangulateFace), so the cells on a face agree: a warped face's triangles away from the apex
  // are cones of their own. Only where a face on the apex is flat with it and not a fan from it
  // do the two sides cut a plane differently.
  auto signFrom = [&](uint32_t apex, bool& exact) {
    int sign = 0;
    exact = true;
    for (size_t f = 0, begin = 0; f < faces.numFaces(); begin = faceEnd[f], ++f) {
      const bool apexFace = onFace(f, apex);
      for (size_t t = begin; t < faceEnd[f]; ++t) {
        const int s = cone(apex, t, apexFace);
        if (s == 0) continue;
        if (s == kFlatOnApexFace) {
          exact = false;
          continue;
        }
        if (s == kFlatElsewhere || (sign != 0 && s != sign)) return 0;
        sign = s;
      }
    }
    return sign;
  };
  // The first exact apex, else the first that sees every cone.
  uint32_t apex = 0;
  int sign = 0;
  for (uint32_t v : verts) {
    bool exact = false;
    const int s = signFrom(v, exact);
    if (s != 0 && (sign == 0 || exact)) {
      apex = v;
      sign = s;
      if (exact) break;
    }
  }
  if (sign == 0) return PolyhedronSplit::NotStarShaped;
  for (size_t f = 0, begin = 0; f < faces.numFaces(); begin = faceEnd[f], ++f) {
    const bool apexFace = onFace(f, apex);
    for (size_t t = begin; t < faceEnd[f]; ++t) {
      const int s = cone(apex, t, apexFace);
      if (s != 1 && s != -1) continue;
      const auto& r = tris[t];
      // VTK's positive order: the base turns towards the apex.
      tets.push_back(sign > 0 ? std::array<uint32_t, 4>{r[0], r[1], r[2], apex}
                              : std::array<uint32_t, 4>{r[0], r[2], r[1], apex});
    }
  }
  return PolyhedronSplit::Ok;
}

}  // namespace sm::mesh
