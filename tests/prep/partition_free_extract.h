// A cluster subset for prep tests, kept here so that prep tests do not depend on src/partition.
#pragma once

#include <map>

#include "mesh/unstructured_mesh.h"

namespace sm::test {

struct Subset {
  mesh::UnstructuredMesh mesh;
  std::vector<uint32_t> original;  // subset vertex -> whole-mesh vertex
};

inline Subset clusterSubset(const mesh::UnstructuredMesh& m, int cluster) {
  Subset s;
  std::map<uint32_t, uint32_t> local;
  for (int t = 0; t < mesh::kNumCellTypes; ++t) {
    const uint32_t nv = mesh::numVerts(mesh::CellType(t));
    for (size_t e = 0; e < m.clusters[t].size(); ++e) {
      if (m.clusters[t][e] != cluster) continue;
      for (uint32_t i = 0; i < nv; ++i) {
        uint32_t g = m.cells[t][e * nv + i];
        auto [it, inserted] = local.emplace(g, uint32_t(s.original.size()));
        if (inserted) s.original.push_back(g);
        s.mesh.cells[t].push_back(it->second);
      }
      s.mesh.clusters[t].push_back(cluster);
    }
  }
  for (uint32_t g : s.original) s.mesh.points.push_back(m.points[g]);
  return s;
}

}  // namespace sm::test
