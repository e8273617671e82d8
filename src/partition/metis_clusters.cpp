// METIS clusters: the solver-like partitioning used when a mesh carries none. METIS's dual graph
// with three common nodes links elements that share a face (triangle or quad) and nothing else,
// for every mix of element types, so one call covers tetrahedra, pyramids, wedges and hexahedra.
#include <metis.h>

#include <algorithm>
#include <limits>

#include "common/check.h"
#include "common/error.h"
#include "partition/partition.h"

namespace sm::partition {
namespace {

using mesh::CellType;
using mesh::UnstructuredMesh;

// Element ranges in one flat numbering: all tetrahedra, then pyramids, wedges, hexahedra.
struct DualInput {
  std::vector<idx_t> eptr, eind;
};

DualInput flatten(const UnstructuredMesh& mesh) {
  uint64_t ids = 0;
  for (const auto& c : mesh.cells) ids += c.size();
  constexpr uint64_t kMax = uint64_t(std::numeric_limits<idx_t>::max());
  if (ids >= kMax || mesh.numPoints() >= kMax)
    throw Error(mesh.source, ": too large for METIS with 32-bit indices (", mesh.numCells(),
                " elements, ", ids, " vertex ids)");
  DualInput in;
  in.eptr.reserve(mesh.numCells() + 1);
  in.eind.reserve(ids);
  in.eptr.push_back(0);
  for (CellType t : mesh::kAllCellTypes) {
    const uint32_t nv = mesh::numVerts(t);
    const auto& cells = mesh.cells[mesh::typeIndex(t)];
    for (size_t e = 0; e < cells.size(); e += nv) {
      for (uint32_t k = 0; k < nv; ++k) in.eind.push_back(idx_t(cells[e + k]));
      in.eptr.push_back(idx_t(in.eind.size()));
    }
  }
  return in;
}

// METIS may leave a part empty (tiny or disconnected meshes). A cluster that exists in name only
// would be a rank with nothing to render, so each empty part takes one element from the largest.
void fillEmptyParts(std::vector<idx_t>& part, int n) {
  std::vector<uint64_t> size(n, 0);
  for (idx_t p : part) ++size[p];
  for (int empty = 0; empty < n; ++empty) {
    if (size[empty] != 0) continue;
    int largest = int(std::max_element(size.begin(), size.end()) - size.begin());
    SM_CHECK_GT(size[largest], 1u);
    for (size_t e = part.size(); e-- > 0;) {
      if (part[e] == largest) {
        part[e] = empty;
        break;
      }
    }
    --size[largest];
    ++size[empty];
  }
}

void storeParts(UnstructuredMesh& mesh, const std::vector<idx_t>& part) {
  size_t flat = 0;
  for (CellType t : mesh::kAllCellTypes) {
    auto& clusters = mesh.clusters[mesh::typeIndex(t)];
    clusters.resize(mesh.numCells(t));
    for (auto& c : clusters) c = int32_t(part[flat++]);
  }
  SM_CHECK_EQ(flat, part.size());
}

}  // namespace

void assignMetisClusters(UnstructuredMesh& mesh, int n, uint64_t seed) {
  if (n < 1) throw Error("the number of clusters must be at least 1, got ", n);
  const uint64_t ne = mesh.numCells();
  if (n == 1 || ne <= 1) {
    for (CellType t : mesh::kAllCellTypes)
      mesh.clusters[mesh::typeIndex(t)].assign(mesh.numCells(t), 0);
    return;
  }
  if (uint64_t(n) >= ne) {
    std::vector<idx_t> part(ne);
    for (uint64_t e = 0; e < ne; ++e) part[e] = idx_t(e);
    storeParts(mesh, part);
    return;
  }
  DualInput in = flatten(mesh);
  idx_t numElems = idx_t(ne), numNodes = idx_t(mesh.numPoints()), ncommon = 3, nparts = n;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  options[METIS_OPTION_SEED] = idx_t(seed % uint64_t(std::numeric_limits<idx_t>::max()));
  idx_t objval = 0;
  std::vector<idx_t> epart(ne), npart(mesh.numPoints());
  int status =
      METIS_PartMeshDual(&numElems, &numNodes, in.eptr.data(), in.eind.data(), nullptr, nullptr,
                         &ncommon, &nparts, nullptr, options, &objval, epart.data(), npart.data());
  if (status == METIS_ERROR_MEMORY)
    throw Error(mesh.source, ": METIS ran out of memory partitioning ", ne, " elements");
  SM_CHECK_MSG(status == METIS_OK, "METIS_PartMeshDual failed with status " << status);
  fillEmptyParts(epart, n);
  storeParts(mesh, epart);
}

std::vector<uint64_t> clusterSizes(const UnstructuredMesh& mesh) {
  std::vector<uint64_t> sizes(std::max(mesh.numClusters(), 0), 0);
  for (const auto& clusters : mesh.clusters)
    for (int32_t c : clusters) {
      SM_CHECK_GE(c, 0);
      ++sizes[c];
    }
  return sizes;
}

}  // namespace sm::partition
