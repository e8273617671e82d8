// Subset meshes: one rank's clusters as a self-contained mesh. Points keep their relative order so
// that the extraction of all clusters reproduces the input exactly, and so that a shared quad
// (split through its smallest vertex id) is split the same way in every extraction.
#include <algorithm>
#include <array>

#include "common/check.h"
#include "partition/partition.h"

namespace sm::partition {

using mesh::CellType;
using mesh::UnstructuredMesh;

ExtractedClusters extractClustersWithPointMap(const UnstructuredMesh& mesh,
                                              const std::vector<int>& clusters,
                                              bool keepUnusedPoints) {
  const int32_t numClusters = mesh.numClusters();
  std::vector<char> wanted(std::max(numClusters, 0), 0);
  for (int c : clusters)
    if (c >= 0 && c < numClusters) wanted[c] = 1;

  // Pass 1: which elements stay, which points they use.
  constexpr uint32_t kUnused = 0xFFFFFFFFu;
  std::vector<uint32_t> newIndex(mesh.numPoints(), kUnused);
  std::array<std::vector<char>, mesh::kNumCellTypes> keep;
  for (CellType t : mesh::kAllCellTypes) {
    const uint32_t ti = mesh::typeIndex(t), nv = mesh::numVerts(t);
    const auto& ids = mesh.cells[ti];
    const auto& cl = mesh.clusters[ti];
    SM_CHECK_EQ(cl.size(), mesh.numCells(t));
    keep[ti].assign(cl.size(), 0);
    for (size_t e = 0; e < cl.size(); ++e) {
      if (cl[e] < 0 || cl[e] >= numClusters || !wanted[cl[e]]) continue;
      keep[ti][e] = 1;
      for (uint32_t k = 0; k < nv; ++k) newIndex[ids[e * nv + k]] = 0;
    }
  }

  if (keepUnusedPoints) {
    const std::vector<uint8_t> used = mesh::usedPoints(mesh);
    for (size_t p = 0; p < used.size(); ++p)
      if (!used[p]) newIndex[p] = 0;
  }

  // Points in their original order.
  ExtractedClusters out;
  UnstructuredMesh& sub = out.mesh;
  sub.source = mesh.source;
  for (size_t p = 0; p < newIndex.size(); ++p) {
    if (newIndex[p] == kUnused) continue;
    newIndex[p] = uint32_t(out.originalPoint.size());
    out.originalPoint.push_back(uint32_t(p));
  }
  sub.points.reserve(out.originalPoint.size());
  for (uint32_t p : out.originalPoint) sub.points.push_back(mesh.points[p]);

  // Pass 2: elements, renumbered.
  for (CellType t : mesh::kAllCellTypes) {
    const uint32_t ti = mesh::typeIndex(t), nv = mesh::numVerts(t);
    const auto& ids = mesh.cells[ti];
    for (size_t e = 0; e < keep[ti].size(); ++e) {
      if (!keep[ti][e]) continue;
      for (uint32_t k = 0; k < nv; ++k) sub.cells[ti].push_back(newIndex[ids[e * nv + k]]);
      sub.clusters[ti].push_back(mesh.clusters[ti][e]);
    }
  }

  for (const auto& f : mesh.fields) {
    mesh::Field g{f.name, {}};
    g.steps.reserve(f.steps.size());
    for (const auto& values : f.steps) {
      SM_CHECK_EQ(values.size(), mesh.numPoints());
      std::vector<float> v;
      v.reserve(out.originalPoint.size());
      for (uint32_t p : out.originalPoint) v.push_back(values[p]);
      g.steps.push_back(std::move(v));
    }
    sub.fields.push_back(std::move(g));
  }
  sub.timeValues = mesh.timeValues;
  sub.cellArrays = mesh.cellArrays;
  return out;
}

UnstructuredMesh extractClusters(const UnstructuredMesh& mesh, const std::vector<int>& clusters) {
  return extractClustersWithPointMap(mesh, clusters).mesh;
}

}  // namespace sm::partition
