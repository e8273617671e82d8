#include "pipeline/rank_pipeline.h"

#include <cstdio>
#include <filesystem>

#include "common/error.h"
#include "common/log.h"
#include "common/timer.h"
#include "prep/cache.h"

namespace sm::app {

PreparedShare prepareShare(RankShare& share, const prep::PrepOptions& options,
                           const std::string& cacheDir, int rank, int ranks) {
  PreparedShare out;
  prep::GlobalFrame frame = prep::makeGlobalFrame(share.wholeBounds);
  std::string path;
  uint64_t key = 0;
  if (!cacheDir.empty() && cacheDir != "none") {
    std::string layout = concat("rank ", rank, " of ", ranks, ", clusters");
    for (int c : share.clusters) layout += concat(" ", c);
    key = prep::cacheKey(share.mesh, frame, options, layout);
    std::error_code ec;
    std::filesystem::create_directories(cacheDir, ec);
    char name[32];
    std::snprintf(name, sizeof name, "%016llx.smprep", (unsigned long long)key);
    path = (std::filesystem::path(cacheDir) / name).string();
    prep::CacheRead cached = prep::readCache(path, key);
    if (cached.status == prep::CacheStatus::Hit) {
      out.rank = std::move(*cached.rank);
      out.fromCache = true;
      log::info("preparation cache hit: ", path);
      return out;
    }
    if (cached.status == prep::CacheStatus::Corrupt || cached.status == prep::CacheStatus::Stale)
      log::warning(path, ": ", cached.reason, "; preparing again");
  }
  // The key was computed above, before preparation takes the geometry out of the mesh.
  prep::PrepResult r = prep::prepareRank(share.mesh, frame, options);
  out.rank = std::move(r.rank);
  out.timings = r.timings;
  if (!path.empty()) prep::writeCache(path, out.rank, key);
  return out;
}

std::vector<float> fieldStep(const mesh::UnstructuredMesh& mesh, const prep::PreparedRank& rank,
                             const std::string& name, uint64_t step) {
  if (rank.numVertices() == 0) return {};
  const mesh::Field* f = mesh.findField(name);
  if (!f) {
    std::string names;
    for (const auto& g : mesh.fields) names += (names.empty() ? "" : ", ") + g.name;
    throw Error("--field: ", mesh.source, " has no point field '", name,
                "' (it has: ", names.empty() ? std::string("none") : names, ")",
                mesh::cellArrayHint(mesh.cellArrays, name));
  }
  if (step >= f->numSteps())
    throw Error("--time: field '", name, "' has ", f->numSteps(), " time steps (0 .. ",
                f->numSteps() - 1, "), not step ", step);
  return prep::gatherScalars(rank, f->steps[step]);
}

}  // namespace sm::app
