#include "prep/shell.h"

#include <algorithm>
#include <numeric>

#include "mesh/unstructured_mesh.h"
#include "prep/vertex_order.h"

namespace sm::prep {

Shell extractShell(const ElementArrays& elements, const ElementArrays& neighbors,
                   const std::vector<float>& positions) {
  Shell shell;
  FaceSlots slots(elements);
  auto emit = [&](uint32_t a, uint32_t b, uint32_t c, uint32_t ref, uint32_t other) {
    shell.indices.insert(shell.indices.end(), {a, b, c});
    shell.refs.push_back(ref);
    shell.other.push_back(other);
  };
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t) {
    const uint32_t nv = gpu::SM_NUM_VERTS[t], nf = gpu::SM_NUM_FACES[t];
    const uint32_t* nb = neighbors[t].data();
    for (uint64_t e = 0; e < slots.elements(t); ++e) {
      const uint32_t* v = elements[t].data() + e * nv;
      for (uint32_t s = 0; s < nf; ++s) {
        if (nb[e * nf + s] != gpu::SM_NO_NEIGHBOR) continue;
        uint32_t f[4];
        uint32_t n = FaceSlots::faceVertices(t, v, s, f);
        uint32_t ref = gpu::smElemRef(uint32_t(e), t);
        if (n == 3) {
          emit(f[0], f[1], f[2], ref, ~0u);
        } else {
          uint32_t tri[6], other[2];
          gpu::smQuadSplit(f[0], f[1], f[2], f[3], tri, other);
          emit(tri[0], tri[1], tri[2], ref, other[0]);
          emit(tri[3], tri[4], tri[5], ref, other[1]);
        }
      }
    }
  }
  sortShellSpatially(shell, positions);
  return shell;
}

void sortShellSpatially(Shell& shell, const std::vector<float>& positions) {
  const size_t n = shell.refs.size();
  if (n < 2) return;
  auto pos = [&](uint32_t v) {
    const size_t i = 3 * size_t(v);  // not 3 * v in 32 bits
    return glm::dvec3(positions[i], positions[i + 1], positions[i + 2]);
  };
  mesh::Bounds b;
  std::vector<glm::dvec3> centroid(n);
  for (size_t i = 0; i < n; ++i) {
    centroid[i] = (pos(shell.indices[3 * i]) + pos(shell.indices[3 * i + 1]) +
                   pos(shell.indices[3 * i + 2])) /
                  3.0;
    b.extend(centroid[i]);
  }
  std::vector<std::pair<uint64_t, uint32_t>> keys(n);
  for (size_t i = 0; i < n; ++i) keys[i] = {mortonCode(centroid[i], b), uint32_t(i)};
  std::sort(keys.begin(), keys.end());
  Shell sorted;
  sorted.indices.resize(shell.indices.size());
  sorted.refs.resize(n);
  sorted.other.resize(n);
  for (size_t i = 0; i < n; ++i) {
    uint32_t src = keys[i].second;
    std::copy_n(&shell.indices[3 * src], 3, &sorted.indices[3 * i]);
    sorted.refs[i] = shell.refs[src];
    sorted.other[i] = shell.other[src];
  }
  shell = std::move(sorted);
}

std::vector<uint32_t> shellAdjacency(const std::vector<uint32_t>& indices) {
  const size_t nt = indices.size() / 3;
  struct Edge {
    uint64_t key;   // min << 32 | max
    uint32_t slot;  // 3 * triangle + k
  };
  std::vector<Edge> edges(3 * nt);
  for (size_t t = 0; t < nt; ++t)
    for (uint32_t k = 0; k < 3; ++k) {
      uint32_t a = indices[3 * t + k], b = indices[3 * t + (k + 1) % 3];
      edges[3 * t + k] = {uint64_t(std::min(a, b)) << 32 | std::max(a, b), uint32_t(3 * t + k)};
    }
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) { return x.key < y.key; });
  std::vector<uint32_t> adj(3 * nt, ~0u);
  for (size_t i = 0; i < edges.size();) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j].key == edges[i].key) ++j;
    if (j - i == 2) {
      adj[edges[i].slot] = edges[i + 1].slot / 3;
      adj[edges[i + 1].slot] = edges[i].slot / 3;
    }
    i = j;
  }
  return adj;
}

}  // namespace sm::prep
