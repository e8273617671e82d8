// Binary cache of prepared rank data, keyed by the rank's input content and layout.
//
// File: a 64-byte header (magic "SMPREP01", format version, key, payload size and checksum) then
// sections (id, element size, count, data, padded to 8 bytes). A file whose key differs is stale;
// one whose checksum, sizes or indices do not add up is corrupt. Both make readCache return
// nothing (with a message), and the caller prepares again and overwrites the file.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "mesh/unstructured_mesh.h"
#include "prep/prepared_rank.h"

namespace sm::prep {

// 2: elements in the order of their smallest vertex (orderElementsByVertex); a version-1 cache
// would still render right, only slower, but a cache is meant to hold what preparation makes now.
inline constexpr uint32_t kCacheFormatVersion = 3;

// Hash of everything preparation depends on: the rank's mesh geometry and cluster ids, the global
// frame, the options, a layout string (e.g. "rank 2 of 4, clusters 3,7") and the format version.
uint64_t cacheKey(const mesh::UnstructuredMesh& rankMesh, const GlobalFrame& frame,
                  const PrepOptions& options, const std::string& layout);

void writeCache(const std::string& path, const PreparedRank& rank, uint64_t key);

enum class CacheStatus { Hit, Missing, Stale, Corrupt };
struct CacheRead {
  CacheStatus status = CacheStatus::Missing;
  std::string reason;  // for Stale and Corrupt
  std::optional<PreparedRank> rank;
};
CacheRead readCache(const std::string& path, uint64_t key);
// Parses a cache image from memory (what readCache does after reading the file; fuzzed).
CacheRead parseCache(const uint8_t* data, size_t size, uint64_t key);

}  // namespace sm::prep
