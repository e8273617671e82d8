// ShaderCache's files (vk/shader_cache.h): what is stored comes back, and a file that cannot be
// trusted is ignored with a warning and counted, never returned. No device is needed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <numeric>
#include <string>
#include <thread>
#include <vector>

#include "vk/shader_cache.h"

namespace sm::vk {
namespace {

namespace fs = std::filesystem;

class ShaderCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("shader-cache-test-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    id_.vendorId = 0x10de;
    id_.deviceId = 42;
    id_.version = 7;
    for (int i = 0; i < 16; ++i) id_.uuid[i] = uint8_t(i * 11);
    payload_.resize(5000);
    std::iota(payload_.begin(), payload_.end(), uint8_t(3));
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string file() const { return (dir_ / "shader-x.bin").string(); }
  std::vector<uint8_t> bytes() const {
    std::ifstream in(file(), std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
  }
  void write(const std::vector<uint8_t>& b) const {
    std::ofstream(file(), std::ios::binary)
        .write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
  }
  // Loads after `damage` changed the stored file: nothing, one warning containing `why`.
  void expectRejected(const std::function<void(std::vector<uint8_t>&)>& damage,
                      const std::string& why) {
    ShaderCache c(dir_.string());
    ASSERT_TRUE(c.store("shader-x.bin", ShaderCache::kShaderBinary, id_, 9, payload_));
    std::vector<uint8_t> b = bytes();
    damage(b);
    write(b);
    ::testing::internal::CaptureStderr();
    EXPECT_TRUE(c.load("shader-x.bin", ShaderCache::kShaderBinary, id_, 9).empty());
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find("warning: ignoring cache file " + file()), std::string::npos) << err;
    EXPECT_NE(err.find(why), std::string::npos) << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_EQ(c.rejected(), 1u);
    EXPECT_EQ(c.hits(), 0u);
  }

  fs::path dir_;
  CacheIdentity id_;
  std::vector<uint8_t> payload_;
};

TEST_F(ShaderCacheTest, StoresAndLoads) {
  ShaderCache c(dir_.string());
  EXPECT_TRUE(c.load("shader-x.bin", ShaderCache::kShaderBinary, id_, 9).empty());
  EXPECT_EQ(c.misses(), 1u);
  ASSERT_TRUE(c.store("shader-x.bin", ShaderCache::kShaderBinary, id_, 9, payload_));
  EXPECT_EQ(c.load("shader-x.bin", ShaderCache::kShaderBinary, id_, 9), payload_);
  EXPECT_EQ(c.hits(), 1u);
  EXPECT_EQ(c.stored(), 1u);
  EXPECT_EQ(bytes().size(), 72 + payload_.size());  // the header, then the payload
  // Nothing is left under a temporary name.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(ShaderCacheTest, NoFolderKeepsNothing) {
  for (const char* folder : {"", "none"}) {
    ShaderCache c(folder);
    EXPECT_FALSE(c.enabled());
    EXPECT_FALSE(c.store("shader-x.bin", ShaderCache::kShaderBinary, id_, 9, payload_));
    EXPECT_TRUE(c.load("shader-x.bin", ShaderCache::kShaderBinary, id_, 9).empty());
  }
  EXPECT_FALSE(fs::exists("none"));
}

TEST_F(ShaderCacheTest, DefaultFolderFollowsTheEnvironment) {
  const char* saved = std::getenv("SHELLMARCH_CACHE_DIR");
  const std::string keep = saved ? saved : "";
  const char* home = std::getenv("HOME");
  const std::string keepHome = home ? home : "";
  ::setenv("SHELLMARCH_CACHE_DIR", "/some/where", 1);
  EXPECT_EQ(ShaderCache::defaultFolder(), "/some/where");
  ::unsetenv("SHELLMARCH_CACHE_DIR");
  ::setenv("XDG_CACHE_HOME", "/xdg", 1);
  EXPECT_EQ(ShaderCache::defaultFolder(), "/xdg/shellmarch");
  ::unsetenv("XDG_CACHE_HOME");
  ::setenv("HOME", "/home/u", 1);
  EXPECT_EQ(ShaderCache::defaultFolder(), "/home/u/.cache/shellmarch");
  if (saved) ::setenv("SHELLMARCH_CACHE_DIR", keep.c_str(), 1);
  if (home) ::setenv("HOME", keepHome.c_str(), 1);
}

TEST_F(ShaderCacheTest, TruncatedFilesAreRejected) {
  expectRejected([](std::vector<uint8_t>& b) { b.resize(b.size() - 1); }, "truncated");
}
TEST_F(ShaderCacheTest, TruncatedHeadersAreRejected) {
  expectRejected([](std::vector<uint8_t>& b) { b.resize(40); }, "truncated (40 bytes)");
}
TEST_F(ShaderCacheTest, CorruptPayloadsAreRejected) {
  expectRejected([](std::vector<uint8_t>& b) { b[b.size() / 2] ^= 0x20; }, "corrupt");
}
TEST_F(ShaderCacheTest, TrailingBytesAreRejected) {
  expectRejected([](std::vector<uint8_t>& b) { b.push_back(0); }, "1 bytes past its end");
}
TEST_F(ShaderCacheTest, OtherFilesAreRejected) {
  expectRejected([](std::vector<uint8_t>& b) { b.assign(100, 'x'); }, "not a shellmarch cache");
}
TEST_F(ShaderCacheTest, NewerFormatsAreRejected) {
  expectRejected([](std::vector<uint8_t>& b) { b[8] = uint8_t(ShaderCache::kFormat + 1); },
                 "written by a newer shellmarch");
}

TEST_F(ShaderCacheTest, OtherDevicesDriversShadersAndKindsAreRejected) {
  ShaderCache c(dir_.string());
  ASSERT_TRUE(c.store("shader-x.bin", ShaderCache::kShaderBinary, id_, 9, payload_));
  CacheIdentity other = id_;
  other.version += 1;  // a driver update
  ::testing::internal::CaptureStderr();
  EXPECT_TRUE(c.load("shader-x.bin", ShaderCache::kShaderBinary, other, 9).empty());
  other = id_;
  other.uuid[3] ^= 1;
  EXPECT_TRUE(c.load("shader-x.bin", ShaderCache::kShaderBinary, other, 9).empty());
  EXPECT_TRUE(c.load("shader-x.bin", ShaderCache::kShaderBinary, id_, 10).empty());
  EXPECT_TRUE(c.load("shader-x.bin", ShaderCache::kPipelineCache, id_, 9).empty());
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("made by another device or driver"), std::string::npos) << err;
  EXPECT_NE(err.find("made for another shader"), std::string::npos) << err;
  EXPECT_NE(err.find("another kind of cache data"), std::string::npos) << err;
  EXPECT_EQ(c.rejected(), 4u);
  // The file is left for the store that replaces it.
  EXPECT_EQ(c.load("shader-x.bin", ShaderCache::kShaderBinary, id_, 9), payload_);
}

TEST_F(ShaderCacheTest, AnUnwritableFolderWarnsOnce) {
  fs::create_directories(dir_);
  std::ofstream((dir_ / "blocker").string()) << "a file, not a folder";
  ShaderCache c((dir_ / "blocker" / "cache").string());
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(c.store("a.bin", ShaderCache::kShaderBinary, id_, 1, payload_));
  EXPECT_FALSE(c.store("b.bin", ShaderCache::kShaderBinary, id_, 2, payload_));
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("cannot write the shader cache in " + (dir_ / "blocker" / "cache").string()),
            std::string::npos)
      << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_EQ(c.stored(), 0u);
}

// Writers replacing a file while readers read it, as ranks and processes sharing a folder do:
// every load is the whole payload of one writer or nothing, never a rejected file.
TEST_F(ShaderCacheTest, ConcurrentWritersAndReadersSeeWholeFiles) {
  ShaderCache c(dir_.string());
  std::vector<std::vector<uint8_t>> payloads(4, payload_);
  for (size_t w = 0; w < payloads.size(); ++w) payloads[w][0] = uint8_t(w);
  std::atomic<bool> stop{false};
  std::atomic<int> whole{0}, bad{0};
  std::vector<std::thread> threads;
  for (size_t w = 0; w < payloads.size(); ++w)
    threads.emplace_back([&, w] {
      for (int i = 0; i < 50; ++i)
        c.store("shader-x.bin", ShaderCache::kShaderBinary, id_, 9, payloads[w]);
    });
  for (int r = 0; r < 2; ++r)
    threads.emplace_back([&] {
      while (!stop) {
        std::vector<uint8_t> got = c.load("shader-x.bin", ShaderCache::kShaderBinary, id_, 9);
        if (got.empty()) continue;
        bool known = std::find(payloads.begin(), payloads.end(), got) != payloads.end();
        (known ? whole : bad)++;
      }
    });
  for (size_t w = 0; w < payloads.size(); ++w) threads[w].join();
  stop = true;
  for (size_t t = payloads.size(); t < threads.size(); ++t) threads[t].join();
  EXPECT_EQ(bad, 0);
  EXPECT_GT(whole, 0);
  EXPECT_EQ(c.rejected(), 0u);
  EXPECT_EQ(c.stored(), 200u);
}

TEST(Fnv1a, KnownValues) {
  EXPECT_EQ(fnv1a({}), 0xcbf29ce484222325ull);
  const uint8_t a[] = {'a'};
  EXPECT_EQ(fnv1a(a), 0xaf63dc4c8601ec8cull);
}

}  // namespace
}  // namespace sm::vk
