// Every input a fuzzer found a bug with, replayed through the loaders' ordinary entry points (the
// normal build, and the sanitizer build of ci/sanitize.sh), plus checks that the fuzz harness
// itself reads what the real entry points read.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

#include "common/error.h"
#include "fuzz_inputs.h"
#include "io/mesh_io.h"

namespace sm::fuzz {
namespace {

namespace fs = std::filesystem;

std::vector<uint8_t> bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// tests/fuzz/regressions/index.tsv: one line per input, "target/name<TAB>outcome<TAB>bug", where
// outcome is "accepted" or a part of the message the input must now be rejected with.
std::map<std::string, std::string> expectedOutcomes(const fs::path& root) {
  std::ifstream in(root / "index.tsv");
  std::map<std::string, std::string> out;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    const size_t a = line.find('\t'), b = line.find('\t', a + 1);
    if (a == std::string::npos || b == std::string::npos) {
      ADD_FAILURE() << "index.tsv: not three columns: " << line;
      continue;
    }
    out[line.substr(0, a)] = line.substr(a + 1, b - a - 1);
  }
  return out;
}

TEST(FuzzRegressions, EveryCommittedInputGivesItsRecordedOutcome) {
  const fs::path root = SHELLMARCH_FUZZ_REGRESSIONS;
  ASSERT_TRUE(fs::is_directory(root)) << root;
  std::map<std::string, std::string> expected = expectedOutcomes(root);
  size_t inputs = 0;
  for (const auto& dir : fs::directory_iterator(root)) {
    if (!dir.is_directory()) continue;
    // A folder that names no target would be skipped silently by ci/fuzz.sh and by this test.
    Target target{};
    ASSERT_NO_THROW(target = targetByName(dir.path().filename().string())) << dir.path();
    for (const auto& file : fs::directory_iterator(dir.path())) {
      const std::string key =
          dir.path().filename().string() + "/" + file.path().filename().string();
      SCOPED_TRACE(key);
      auto it = expected.find(key);
      if (it == expected.end()) {
        ADD_FAILURE() << "not in index.tsv: every input needs its outcome and its bug recorded";
        continue;
      }
      try {
        const std::string outcome = runInput(target, bytesOf(file.path()));
        if (it->second == "accepted")
          EXPECT_EQ(outcome, "") << "rejected";
        else
          EXPECT_NE(outcome.find(it->second), std::string::npos) << "outcome: " << outcome;
      } catch (const FuzzBug& e) {
        ADD_FAILURE() << e.what();
      }
      expected.erase(it);
      ++inputs;
    }
  }
  for (const auto& [key, outcome] : expected) ADD_FAILURE() << "index.tsv names a missing " << key;
  EXPECT_GT(inputs, 0u) << "no regression inputs under " << root;
}

// The .pvtu harness serves pieces from memory through readPvtu's OpenFile hook: the same bundle
// as files must give the same mesh, or the fuzzer would be testing something else.
TEST(FuzzHarness, PvtuBundleReadsAsTheFilesDo) {
  const fs::path data = SHELLMARCH_IO_TEST_DATA;
  std::vector<uint8_t> bundle = bytesOf(data / "weld.pvtu");
  for (int k = 0; k < 3; ++k) {
    bundle.insert(bundle.end(), kPieceSeparator.begin(), kPieceSeparator.end());
    std::vector<uint8_t> piece = bytesOf(data / "weld" / ("weld_" + std::to_string(k) + ".vtu"));
    bundle.insert(bundle.end(), piece.begin(), piece.end());
  }
  const mesh::UnstructuredMesh memory = readPvtuBundle(bundle);
  const mesh::UnstructuredMesh files = io::readMesh((data / "weld.pvtu").string());
  ASSERT_GT(files.numCells(), 0u);
  EXPECT_EQ(memory.points, files.points);
  EXPECT_EQ(memory.cells, files.cells);
  EXPECT_EQ(memory.clusters, files.clusters);
  ASSERT_EQ(memory.fields.size(), files.fields.size());
  EXPECT_EQ(memory.fields[0].steps, files.fields[0].steps);
  // A piece the bundle lacks is a missing file, reported under the piece's name.
  std::vector<uint8_t> two(
      bundle.begin(),
      bundle.begin() + std::string_view(reinterpret_cast<const char*>(bundle.data()), bundle.size())
                           .rfind(kPieceSeparator));
  try {
    readPvtuBundle(two);
    ADD_FAILURE() << "a bundle without piece 2 was read";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("fuzz/weld/weld_2.vtu: cannot open"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace sm::fuzz
