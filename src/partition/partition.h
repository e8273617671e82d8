// Clusters and ranks. A cluster is a solver partition (a .pvtu piece, a cluster cell array, or a
// METIS part); a rank renders one or more clusters, merged into one volume.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/unstructured_mesh.h"

namespace sm::partition {

// Splits the mesh into n clusters with METIS on the element dual graph (elements adjacent when
// they share a face: 3 common nodes, like mpmetis -gtype=dual -ncommon=3) and stores the part of
// every element in mesh.clusters. Deterministic for a given mesh and n. n = 1 sets all to 0.
// Every cluster 0 .. n-1 gets at least one element; with n >= the element count each element is
// its own cluster (so there are only as many clusters as elements). Throws sm::Error for n < 1.
void assignMetisClusters(mesh::UnstructuredMesh& mesh, int n, uint64_t seed = 1);

// Elements per cluster id (index = cluster id).
std::vector<uint64_t> clusterSizes(const mesh::UnstructuredMesh& mesh);

// Clusters to ranks, balancing element counts: largest cluster first onto the least loaded rank
// (ties: lowest rank). clusterToRank[c] is the rank of cluster c; empty clusters go to rank 0.
// Equal sizes are taken in cluster order. Throws sm::Error for ranks < 1.
std::vector<int> assignClustersToRanks(const std::vector<uint64_t>& clusterSizes, int ranks);

// The elements of the given clusters as one mesh: unused points dropped, points renumbered in
// their original order, fields and cluster ids kept. Faces between these clusters are shared by
// vertex ids (as in the input), so preparation sees them as interior. Time values and the source
// name are copied; the counts of skipped and fixed cells stay with the input. Ids in `clusters`
// that the mesh does not have select nothing.
mesh::UnstructuredMesh extractClusters(const mesh::UnstructuredMesh& mesh,
                                       const std::vector<int>& clusters);

// extractClusters, also telling where each extracted point came from: originalPoint[i] is the
// index in `mesh` of point i of the result (increasing).
struct ExtractedClusters {
  mesh::UnstructuredMesh mesh;
  std::vector<uint32_t> originalPoint;
};
// With keepUnusedPoints, the points that no element of `mesh` uses come along too (in their
// place in point order): the one share that takes them keeps their field values, so that the
// ranges over all shares count every point, as the whole mesh's do.
ExtractedClusters extractClustersWithPointMap(const mesh::UnstructuredMesh& mesh,
                                              const std::vector<int>& clusters,
                                              bool keepUnusedPoints = false);

}  // namespace sm::partition
