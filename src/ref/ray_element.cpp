#include "ref/ray_element.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/common.hpp>

#include "common/check.h"

namespace sm::ref {

using mesh::CellType;

namespace {

struct Vertex {
  uint32_t id;
  glm::dvec3 p;  // in the sheared ray frame
};

struct Hit {
  double t;
  int side;  // +1 entering, -1 leaving
};

// Edge function of the directed edge P -> Q at the ray (the origin of the sheared frame); the
// caller always passes P with the smaller global id, so both triangles that share an edge
// evaluate the same expression. Zero is resolved by the (eps, eps^2) shift of the ray: the
// function is linear in the ray's position with gradient (Q.y - P.y, P.x - Q.x).
int edgeSign(const glm::dvec3& p, const glm::dvec3& q, double& e) {
  e = q.x * p.y - q.y * p.x;
  if (e != 0.0) return e > 0.0 ? 1 : -1;
  double dy = q.y - p.y;
  if (dy != 0.0) return dy > 0.0 ? 1 : -1;
  double dx = p.x - q.x;
  if (dx != 0.0) return dx > 0.0 ? 1 : -1;
  return 0;  // the edge is seen end-on: the triangle has no area in the ray's view
}

// Tests triangle (a, b, c), wound outward, against the ray.
bool hitTriangle(Vertex a, Vertex b, Vertex c, Hit& hit) {
  int parity = 1;  // +1 when the sorted order has the original winding
  if (b.id < a.id) std::swap(a, b), parity = -parity;
  if (c.id < b.id) std::swap(b, c), parity = -parity;
  if (b.id < a.id) std::swap(a, b), parity = -parity;
  double u, v, w;
  int su = edgeSign(b.p, c.p, u);   // weight of a
  int sv = -edgeSign(a.p, c.p, v);  // weight of b: the edge c -> a, evaluated as a -> c
  v = -v;
  int sw = edgeSign(a.p, b.p, w);  // weight of c
  if (su == 0 || su != sv || su != sw) return false;
  double det = u + v + w;
  if (det == 0.0) return false;
  double t = (u * a.p.z + v * b.p.z + w * c.p.z) / det;
  if (!std::isfinite(t)) return false;
  // The sheared frame preserves orientation and looks along +z, so a triangle whose projection
  // is clockwise (positive edge functions in the original winding) faces the ray: an entry.
  hit = {t, su * parity > 0 ? 1 : -1};
  return true;
}

// Entries before exits at equal distance: touching pieces merge, grazes become empty.
bool before(const Hit& x, const Hit& y) {
  return x.t < y.t || (x.t == y.t && x.side > y.side);
}

int localIndex(std::span<const uint32_t> ids, uint32_t nv, uint32_t globalId) {
  for (uint32_t i = 0; i < nv; ++i)
    if (ids[i] == globalId) return int(i);
  SM_CHECK_MSG(false, "vertex " << globalId << " is not in the element");
  return 0;
}

}  // namespace

RayFrame::RayFrame(const glm::dvec3& origin, const glm::dvec3& dir) : origin_(origin) {
  glm::dvec3 a = glm::abs(dir);
  SM_CHECK_MSG(std::isfinite(a.x + a.y + a.z) && a.x + a.y + a.z > 0.0,
               "bad ray direction " << dir.x << " " << dir.y << " " << dir.z);
  kz_ = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  kx_ = (kz_ + 1) % 3;
  ky_ = (kx_ + 1) % 3;
  if (dir[kz_] < 0.0) std::swap(kx_, ky_);  // keeps the frame's orientation
  sx_ = dir[kx_] / dir[kz_];
  sy_ = dir[ky_] / dir[kz_];
  sz_ = 1.0 / dir[kz_];
}

glm::dvec3 RayFrame::project(const glm::dvec3& p) const {
  glm::dvec3 a = p - origin_;
  return {a[kx_] - sx_ * a[kz_], a[ky_] - sy_ * a[kz_], sz_ * a[kz_]};
}

int elementIntervals(const RayFrame& ray, CellType type, std::span<const uint32_t> ids,
                     std::span<const glm::dvec3> points, Interval* out) {
  const uint32_t nv = mesh::numVerts(type);
  Vertex v[gpu::SM_MAX_VERTS];
  for (uint32_t i = 0; i < nv; ++i) v[i] = {ids[i], ray.project(points[ids[i]])};
  Hit hits[12];
  int numHits = 0;
  auto test = [&](int a, int b, int c) {
    if (hitTriangle(v[a], v[b], v[c], hits[numHits])) ++numHits;
  };
  for (uint32_t f = 0; f < mesh::numFaces(type); ++f) {
    int a = int(mesh::faceVert(type, f, 0)), b = int(mesh::faceVert(type, f, 1));
    int c = int(mesh::faceVert(type, f, 2));
    if (mesh::faceSize(type, f) == 3) {
      test(a, b, c);
      continue;
    }
    int d = int(mesh::faceVert(type, f, 3));
    uint32_t tri[6], other[2];
    gpu::smQuadSplit(ids[a], ids[b], ids[c], ids[d], tri, other);
    int l[6];
    for (int k = 0; k < 6; ++k) l[k] = localIndex(ids, nv, tri[k]);
    test(l[0], l[1], l[2]);
    test(l[3], l[4], l[5]);
  }
  for (int i = 1; i < numHits; ++i) {  // insertion sort: at most 12 hits
    Hit h = hits[i];
    int j = i;
    for (; j > 0 && before(h, hits[j - 1]); --j) hits[j] = hits[j - 1];
    hits[j] = h;
  }
  int count = 0, winding = 0;
  double start = 0.0;
  for (int i = 0; i < numHits; ++i) {
    int next = winding + hits[i].side;
    if (winding <= 0 && next > 0) start = hits[i].t;
    if (winding > 0 && next <= 0 && hits[i].t > start) out[count++] = {start, hits[i].t};
    winding = next;
  }
  SM_DCHECK(count <= kMaxElementIntervals);
  return count;
}

}  // namespace sm::ref
