#include <gtest/gtest.h>

#include <fstream>

#include "common/file_util.h"
#include "prep/cache.h"
#include "prep/prepare.h"
#include "support/test_meshes.h"
#include "support/test_support.h"

namespace sm::prep {
namespace {

struct Fixture {
  PreparedRank rank;
  uint64_t key;
};

Fixture prepared() {
  auto m = test::kuhnTetGrid(2);
  auto frame = makeGlobalFrame(m.bounds());
  uint64_t key = cacheKey(m, frame, PrepOptions{}, "rank 0 of 1");
  return {prepareRank(m, frame, PrepOptions{}).rank, key};
}

void expectEqual(const PreparedRank& a, const PreparedRank& b) {
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.vertexSource, b.vertexSource);
  EXPECT_EQ(a.elements, b.elements);
  EXPECT_EQ(a.neighbors, b.neighbors);
  EXPECT_EQ(a.elementCount, b.elementCount);
  EXPECT_EQ(a.shellIndices, b.shellIndices);
  EXPECT_EQ(a.shellRefs, b.shellRefs);
  EXPECT_EQ(a.shellOther, b.shellOther);
  EXPECT_EQ(a.shellAdjacency, b.shellAdjacency);
  EXPECT_EQ(a.frame.origin, b.frame.origin);
  EXPECT_EQ(a.compact, b.compact);
}

TEST(Cache, RoundTrip) {
  auto f = prepared();
  std::string path = test::outputDir("cache") + "/round.smprep";
  writeCache(path, f.rank, f.key);
  auto r = readCache(path, f.key);
  ASSERT_EQ(r.status, CacheStatus::Hit) << r.reason;
  expectEqual(*r.rank, f.rank);
}

TEST(Cache, KeyDependsOnInputLayoutAndOptions) {
  auto a = test::kuhnTetGrid(2), b = test::kuhnTetGrid(2, 1.0, glm::dvec3(0, 0, 1e-9));
  auto frame = makeGlobalFrame(a.bounds());
  uint64_t k = cacheKey(a, frame, PrepOptions{}, "rank 0 of 1");
  EXPECT_EQ(k, cacheKey(a, frame, PrepOptions{}, "rank 0 of 1"));
  EXPECT_NE(k, cacheKey(b, frame, PrepOptions{}, "rank 0 of 1"));
  EXPECT_NE(k, cacheKey(a, frame, PrepOptions{}, "rank 1 of 2"));
  EXPECT_NE(k, cacheKey(a, frame, PrepOptions{false}, "rank 0 of 1"));
}

TEST(Cache, StaleAndMissingAreDetected) {
  auto f = prepared();
  std::string path = test::outputDir("cache") + "/stale.smprep";
  writeCache(path, f.rank, f.key);
  EXPECT_EQ(readCache(path, f.key + 1).status, CacheStatus::Stale);
  EXPECT_EQ(readCache(path + ".nope", f.key).status, CacheStatus::Missing);
}

TEST(Cache, EveryTruncationAndByteFlipIsCaught) {
  auto f = prepared();
  std::string path = test::outputDir("cache") + "/corrupt.smprep";
  writeCache(path, f.rank, f.key);
  auto bytes = readFile(path);
  for (size_t cut = 0; cut < bytes.size(); cut += 1 + bytes.size() / 97) {
    auto r = parseCache(bytes.data(), cut, f.key);
    EXPECT_EQ(r.status, CacheStatus::Corrupt) << "truncated at " << cut;
    EXPECT_FALSE(r.rank.has_value());
  }
  for (size_t at = 64; at < bytes.size(); at += 1 + bytes.size() / 61) {
    auto copy = bytes;
    copy[at] ^= 0x5A;
    EXPECT_EQ(parseCache(copy.data(), copy.size(), f.key).status, CacheStatus::Corrupt)
        << "flip at " << at;
  }
}

// A cache whose counts pass the shaders' 32-bit indices is refused as corrupt (a cache that
// preparation wrote never holds one), before its arrays are looked at.
TEST(Cache, CountsPastTheShaderIndexRangeAreCorrupt) {
  auto f = prepared();
  f.rank.elementCount[gpu::SM_HEX] = maxElementsOnRank(gpu::SM_HEX, f.rank.compact) + 1;
  std::string path = test::outputDir("cache") + "/huge.smprep";
  writeCache(path, f.rank, f.key);
  auto r = readCache(path, f.key);
  EXPECT_EQ(r.status, CacheStatus::Corrupt);
  EXPECT_NE(r.reason.find("hexahedra on one rank"), std::string::npos) << r.reason;
}

}  // namespace
}  // namespace sm::prep
