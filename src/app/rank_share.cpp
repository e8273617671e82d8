#include "app/rank_share.h"

#include <algorithm>
#include <limits>

#include "common/error.h"
#include "common/file_util.h"
#include "common/log.h"
#include "partition/partition.h"

namespace sm::app {
namespace {

mesh::Bounds globalBounds(const mesh::Bounds& local, Collectives& coll) {
  const double inf = std::numeric_limits<double>::infinity();
  mesh::Bounds b;
  for (int a = 0; a < 3; ++a) {
    b.lo[a] = coll.min(local.empty ? inf : local.lo[a]);
    b.hi[a] = coll.max(local.empty ? -inf : local.hi[a]);
  }
  b.empty = !(b.lo.x <= b.hi.x);
  if (b.empty) b = mesh::Bounds{};
  return b;
}

std::vector<int> clustersOfRank(const std::vector<int>& clusterToRank, int rank) {
  std::vector<int> mine;
  for (size_t c = 0; c < clusterToRank.size(); ++c)
    if (clusterToRank[c] == rank) mine.push_back(int(c));
  return mine;
}

RankShare readPieces(const std::string& path, const ShareOptions& o, Collectives& coll) {
  std::vector<uint64_t> sizes = io::pieceCellCounts(path);
  std::vector<int> toRank = partition::assignClustersToRanks(sizes, coll.size());
  RankShare s;
  s.totalClusters = int(sizes.size());
  s.clusters = clustersOfRank(toRank, coll.rank());
  if (!s.clusters.empty()) {
    io::ReadOptions read = o.read;
    read.pieces = s.clusters;
    s.mesh = io::readMesh(path, read);
  } else {
    s.mesh.source = path;  // a rank with no clusters renders nothing, but takes part
  }
  return s;
}

RankShare readWhole(const std::string& path, const ShareOptions& o, Collectives& coll) {
  mesh::UnstructuredMesh whole = io::readMesh(path, o.read);
  if (o.metisClusters > 0) partition::assignMetisClusters(whole, o.metisClusters);
  std::vector<uint64_t> sizes = partition::clusterSizes(whole);
  std::vector<int> toRank = partition::assignClustersToRanks(sizes, coll.size());
  RankShare s;
  s.totalClusters = int(sizes.size());
  s.clusters = clustersOfRank(toRank, coll.rank());
  if (coll.size() == 1) {
    s.mesh = std::move(whole);
  } else {
    s.mesh = partition::extractClusters(whole, s.clusters);
    s.mesh.source = path;
  }
  return s;
}

}  // namespace

RankShare loadRankShare(const std::string& path, const ShareOptions& o, Collectives& coll) {
  bool pieces = fileExtension(path) == ".pvtu" && o.metisClusters == 0;
  RankShare s = pieces ? readPieces(path, o, coll) : readWhole(path, o, coll);
  s.wholeBounds = globalBounds(s.mesh.bounds(), coll);
  render::ElementSizeSum local = render::elementSizeSum(s.mesh);
  s.elementSize.sum = coll.sum(local.sum);
  s.elementSize.count = coll.sum(local.count);
  s.wholeElements = s.elementSize.count;
  if (s.wholeElements == 0)
    throw Error(path, ": no tetrahedra, pyramids, wedges or hexahedra to render");
  return s;
}

}  // namespace sm::app
