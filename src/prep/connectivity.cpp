#include "prep/connectivity.h"

#include <algorithm>

#include "common/check.h"
#include "common/error.h"
#include "mesh/cell_type.h"

namespace sm::prep {
namespace {

// A face's vertices other than its smallest, sorted; c = ~0u for triangles.
struct FaceKey {
  uint32_t a, b, c;
  uint32_t rest;  // what identifies the element beside the face (faceVertexSet): a duplicate filter
  uint64_t slot;
  bool operator<(const FaceKey& o) const {
    if (a != o.a) return a < o.a;
    if (b != o.b) return b < o.b;
    return c < o.c;
  }
  bool sameFace(const FaceKey& o) const { return a == o.a && b == o.b && c == o.c; }
};

uint32_t faceMin(const uint32_t* f, uint32_t n) {
  uint32_t m = f[0];
  for (uint32_t i = 1; i < n; ++i) m = std::min(m, f[i]);
  return m;
}

inline void order2(uint32_t& a, uint32_t& b) {
  if (b < a) std::swap(a, b);
}

// Sorting network on 3 or 4 ids (the 4th is ~0u for triangles, so it stays last).
FaceKey makeKey(const uint32_t* f, uint32_t n, uint32_t rest, uint64_t slot) {
  uint32_t a = f[0], b = f[1], c = f[2], d = n == 4 ? f[3] : ~0u;
  order2(a, b);
  order2(c, d);
  order2(a, c);
  order2(b, d);
  order2(b, c);
  return FaceKey{b, c, d, rest, slot};
}

// A face's vertex ids in any order (matching compares sets). Tet slot k is the face opposite the
// vertex of rank k: the other three of the sorted four, found without FaceSlots::vtkFace's rank
// search, which made up a sixth of preparation's time (measured in commit 2e30e1d). `rest`: the
// vertex opposite a tet's face, the sum of the ids of other elements; two elements of one type that
// share a face and their `rest` may be the same cell (sameCell decides).
inline uint32_t faceVertexSet(uint32_t type, const uint32_t* v, uint32_t slot, uint32_t out[4],
                              uint32_t& rest) {
  if (type != gpu::SM_TET) {
    rest = 0;
    for (uint32_t k = 0; k < gpu::SM_NUM_VERTS[type]; ++k) rest += v[k];
    return FaceSlots::faceVertices(type, v, slot, out);
  }
  uint32_t s[4] = {v[0], v[1], v[2], v[3]};
  order2(s[0], s[1]);
  order2(s[2], s[3]);
  order2(s[0], s[2]);
  order2(s[1], s[3]);
  order2(s[1], s[2]);
  for (uint32_t i = 0, n = 0; i < 4; ++i)
    if (i != slot) out[n++] = s[i];
  rest = s[slot];
  return 3;
}

// Calls fn(globalSlot, faceVertexIds, n) for every face slot in order. Tet faces are listed by
// vertex set only (their winding is irrelevant for matching).
template <typename Fn>
void forEachFace(const ElementArrays& elements, const FaceSlots& slots, Fn&& fn) {
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t) {
    const uint32_t nv = gpu::SM_NUM_VERTS[t], nf = gpu::SM_NUM_FACES[t];
    const uint32_t* v = elements[t].data();
    uint64_t g = slots.begin(t);
    for (uint64_t e = 0; e < slots.elements(t); ++e, v += nv) {
      for (uint32_t s = 0; s < nf; ++s, ++g) {
        uint32_t f[4], rest;
        uint32_t n = faceVertexSet(t, v, s, f, rest);
        fn(g, f, n);
      }
    }
  }
}

// Whether two elements are the same cell (the same type and vertex set): a duplicate in the input.
// Called for elements that share a face, so a cheap filter (sum and xor of the ids) decides most.
bool sameCell(const ElementArrays& elements, const FaceSlots::Slot& s0, const FaceSlots::Slot& s1) {
  if (s0.type != s1.type) return false;
  const uint32_t nv = gpu::SM_NUM_VERTS[s0.type];
  const uint32_t* a = elements[s0.type].data() + uint64_t(s0.element) * nv;
  const uint32_t* b = elements[s1.type].data() + uint64_t(s1.element) * nv;
  uint64_t sumA = 0, sumB = 0;
  uint32_t xorA = 0, xorB = 0;
  for (uint32_t i = 0; i < nv; ++i) {
    sumA += a[i];
    sumB += b[i];
    xorA ^= a[i];
    xorB ^= b[i];
  }
  if (sumA != sumB || xorA != xorB) return false;
  // Every id of one is among the other's (ids of an element are distinct, counts equal).
  for (uint32_t i = 0; i < nv; ++i)
    if (std::find(b, b + nv, a[i]) == b + nv) return false;
  return true;
}

std::string elementName(const FaceSlots::Slot& s) {
  return concat(mesh::cellTypeName(mesh::CellType(s.type)), " #", s.element);
}

std::string at(const VertexPosition& where, uint32_t v) {
  if (!where) return "";
  const glm::dvec3 p = where(v);
  return concat(" at (", p.x, ", ", p.y, ", ", p.z, ")");
}

uint32_t firstVertex(const ElementArrays& elements, const FaceSlots::Slot& s) {
  const uint32_t nv = gpu::SM_NUM_VERTS[s.type];
  const uint32_t* v = elements[s.type].data() + uint64_t(s.element) * nv;
  return *std::min_element(v, v + nv);
}

// Matching would pair every face of a duplicated cell with its twin, hiding both from the shell
// (nothing of them would be drawn) or, beside a neighbour, make a face look shared by three.
[[noreturn]] void duplicateCells(const std::string& source, const ElementArrays& elements,
                                 const VertexPosition& where, const FaceSlots::Slot& s0,
                                 const FaceSlots::Slot& s1) {
  throw Error(source, ": two ", mesh::cellTypePluralName(mesh::CellType(s0.type)),
              " have the same vertices (a duplicated cell", at(where, firstVertex(elements, s0)),
              "; ", elementName(s0), " and #", s1.element,
              " in this rank's element order): remove the duplicate");
}

[[noreturn]] void nonManifold(const std::string& source, const ElementArrays& elements,
                              const VertexPosition& where, const FaceSlots& slots,
                              const FaceKey* run, size_t count, uint32_t minVertex) {
  for (size_t i = 0; i < count; ++i)
    for (size_t j = i + 1; j < count; ++j)
      if (sameCell(elements, slots.decode(run[i].slot), slots.decode(run[j].slot)))
        duplicateCells(source, elements, where, slots.decode(run[i].slot),
                       slots.decode(run[j].slot));
  std::string elems;
  for (size_t i = 0; i < count && i < 4; ++i)
    elems += concat(i ? ", " : "", elementName(slots.decode(run[i].slot)));
  throw Error(source, ": face (", minVertex, ", ", run[0].a, ", ", run[0].b,
              run[0].c != ~0u ? concat(", ", run[0].c) : std::string(), ")", at(where, minVertex),
              " is shared by ", count, " elements (", elems, count > 4 ? ", ..." : "",
              "); a face may have at most two");
}

}  // namespace

ConnectivityStats computeConnectivity(const ElementArrays& elements, uint64_t numVertices,
                                      ElementArrays& neighbors, const std::string& source,
                                      const VertexPosition& where) {
  FaceSlots slots(elements);
  const uint64_t total = slots.total();
  if (total >= 0xFFFFFFFFull)
    throw Error(source, ": ", total,
                " element faces on one rank (at most 2^32 - 1); use more ranks");
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t)
    neighbors[t].assign(slots.elements(t) * gpu::SM_NUM_FACES[t], gpu::SM_NO_NEIGHBOR);

  // Counting sort of face slots by their smallest vertex.
  std::vector<uint32_t> start(numVertices + 1, 0);
  forEachFace(elements, slots,
              [&](uint64_t, const uint32_t* f, uint32_t n) { ++start[faceMin(f, n) + 1]; });
  for (uint64_t v = 0; v < numVertices; ++v) start[v + 1] += start[v];
  std::vector<uint32_t> bucket(total);
  {
    std::vector<uint32_t> cursor(start.begin(), start.end() - 1);
    forEachFace(elements, slots, [&](uint64_t g, const uint32_t* f, uint32_t n) {
      bucket[cursor[faceMin(f, n)]++] = uint32_t(g);
    });
  }

  ConnectivityStats stats;
  std::vector<FaceKey> keys;
  auto neighborRef = [&](const FaceSlots::Slot& s) { return gpu::smElemRef(s.element, s.type); };
  for (uint64_t v = 0; v < numVertices; ++v) {
    uint32_t b = start[v], e = start[v + 1];
    if (b == e) continue;
    keys.clear();
    for (uint32_t i = b; i < e; ++i) {
      auto s = slots.decode(bucket[i]);
      const uint32_t* ev =
          elements[s.type].data() + uint64_t(s.element) * gpu::SM_NUM_VERTS[s.type];
      uint32_t f[4], rest;
      uint32_t n = faceVertexSet(s.type, ev, s.slot, f, rest);
      keys.push_back(makeKey(f, n, rest, bucket[i]));
    }
    // Buckets hold a few dozen faces: insertion sort beats std::sort here.
    for (size_t i = 1; i < keys.size(); ++i)
      for (size_t j = i; j > 0 && keys[j] < keys[j - 1]; --j) std::swap(keys[j], keys[j - 1]);
    for (size_t i = 0; i < keys.size();) {
      size_t j = i + 1;
      while (j < keys.size() && keys[j].sameFace(keys[i])) ++j;
      if (j - i == 2) {
        auto s0 = slots.decode(keys[i].slot), s1 = slots.decode(keys[i + 1].slot);
        if (keys[i].rest == keys[i + 1].rest && sameCell(elements, s0, s1))
          duplicateCells(source, elements, where, s0, s1);
        neighbors[s0.type][uint64_t(s0.element) * gpu::SM_NUM_FACES[s0.type] + s0.slot] =
            neighborRef(s1);
        neighbors[s1.type][uint64_t(s1.element) * gpu::SM_NUM_FACES[s1.type] + s1.slot] =
            neighborRef(s0);
        ++stats.interiorFaces;
      } else if (j - i == 1) {
        ++stats.boundaryFaces;
      } else {
        nonManifold(source, elements, where, slots, &keys[i], j - i, uint32_t(v));
      }
      i = j;
    }
  }
  return stats;
}

}  // namespace sm::prep
