// Writes preparation caches of a mesh file, compact and plain, as seeds for the cache fuzzer:
//   fuzz_make_cache_seed MESH OUT_DIR
// Seeds written by the real writer give the fuzzer every section in a valid layout to mutate.
#include <cstdio>
#include <exception>

#include "common/file_util.h"
#include "common/log.h"
#include "io/mesh_io.h"
#include "prep/cache.h"
#include "prep/prepare.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s MESH OUT_DIR\n", argv[0]);
    return 2;
  }
  try {
    sm::log::setLevel(sm::log::Level::Quiet);
    for (bool compact : {true, false}) {
      sm::mesh::UnstructuredMesh m = sm::io::readMesh(argv[1]);
      sm::prep::GlobalFrame frame = sm::prep::makeGlobalFrame(m.bounds());
      const uint64_t key = sm::prep::cacheKey(m, frame, {compact}, "seed");
      sm::prep::PrepResult r = sm::prep::prepareRank(m, frame, {compact});
      const std::string name = compact ? "compact.smprep" : "plain.smprep";
      sm::prep::writeCache(sm::joinPath(argv[2], name), r.rank, key);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_make_cache_seed: %s\n", e.what());
    return 1;
  }
  return 0;
}
