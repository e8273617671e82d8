// Count dumps and comparison images: the tools around the compositor and its benchmark.
#include <gtest/gtest.h>
#include <pthread.h>
#include <sys/resource.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <string>

#include "compositor/tools/count_dump.h"
#include "compositor/tools/image_compare.h"

namespace sm::comp {
namespace {

std::string tempPath(const char* name) {
  return ::testing::TempDir() + name;
}

TEST(CompositorCountDump, RoundTripsRanksInAnyOrder) {
  const std::string path = tempPath("counts.smfc");
  std::vector<std::vector<uint32_t>> counts = {{1, 2, 3, 4, 5, 6}, {0, 0, 7, 0, 0, 8}};
  CountDumpWriter w(path, 3, 2, 2);
  for (const auto& c : counts) w.append(c);
  w.close();
  CountDumpReader r(path);
  EXPECT_EQ(r.width(), 3u);
  EXPECT_EQ(r.height(), 2u);
  EXPECT_EQ(r.ranks(), 2u);
  std::vector<uint32_t> got;
  r.read(1, got);
  EXPECT_EQ(got, counts[1]);
  r.read(0, got);
  EXPECT_EQ(got, counts[0]);
  EXPECT_THROW(r.read(2, got), std::runtime_error);
  std::remove(path.c_str());
}

TEST(CompositorCountDump, RejectsWrongSizesAndForeignFiles) {
  const std::string path = tempPath("short.smfc");
  std::remove(path.c_str());
  {
    CountDumpWriter w(path, 2, 2, 2);
    EXPECT_THROW(w.append(std::vector<uint32_t>(3)), std::runtime_error);
    w.append(std::vector<uint32_t>(4));
    EXPECT_THROW(w.close(), std::runtime_error) << "one rank missing";
  }
  // An unfinished dump never takes the name of a whole one, nor stays behind as a part.
  EXPECT_FALSE(std::ifstream(path).good());
  EXPECT_FALSE(std::ifstream(path + ".part").good());
  EXPECT_THROW(CountDumpWriter(path, 0, 2, 1), std::runtime_error) << "empty image";
  EXPECT_THROW(CountDumpWriter(path, 2, 2, 0), std::runtime_error) << "no ranks";
  EXPECT_FALSE(std::ifstream(path + ".part").good()) << "a refused dump leaves no part behind";
  {  // A dump cut short on disk (a full disk, a copy interrupted) is caught by the reader.
    CountDumpWriter w(path, 2, 2, 2);
    w.append(std::vector<uint32_t>(4));
    w.append(std::vector<uint32_t>(4));
    w.close();
  }
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 4);
  EXPECT_THROW(CountDumpReader{path}, std::runtime_error) << "truncated";
  std::ofstream(path) << "P6 not a dump";
  EXPECT_THROW(CountDumpReader{path}, std::runtime_error);
  std::remove(path.c_str());
}

TEST(CompositorImageCompare, DifferenceAndHeatmap) {
  std::vector<glm::vec4> a = {{0, 0, 0, 0}, {1, 0, 0, 1}}, b = {{0, 0, 0, 0}, {0, 0, 0, 1}};
  std::vector<float> d = l2Difference(a, b);
  EXPECT_EQ(d, (std::vector<float>{0.0f, 1.0f}));
  std::vector<glm::vec4> h = heatmap(std::span<const float>(d));
  EXPECT_EQ(h[0], glm::vec4(0, 0, 0, 1));
  EXPECT_GT(h[1].r + h[1].g + h[1].b, 2.5f) << "the maximum maps to the bright end";
  std::vector<uint32_t> counts = {0, 5, 10};
  std::vector<glm::vec4> hc = heatmap(std::span<const uint32_t>(counts), 5.0f);
  EXPECT_EQ(hc[1], hc[2]) << "values above the maximum saturate";
  EXPECT_THROW(l2Difference(a, std::vector<glm::vec4>(1)), std::invalid_argument);
  EXPECT_EQ(sumCounts({{1, 2}, {3, 4}}), (std::vector<uint32_t>{4, 6}));
  EXPECT_THROW(sumCounts({{1, 2}, {3}}), std::invalid_argument);
}

}  // namespace
}  // namespace sm::comp
