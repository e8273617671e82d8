#include <gtest/gtest.h>

#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "common/error.h"
#include "io_test_util.h"
#include "support/test_support.h"

namespace sm::app {
namespace {

// Runs `shellmarch info ARGS...` through the real command registration and returns its stdout.
std::string runInfo(std::vector<std::string> args) {
  CLI::App app;
  registerInfo(app);
  args.insert(args.begin(), {"shellmarch", "info"});
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  std::ostringstream captured;
  std::streambuf* old = std::cout.rdbuf(captured.rdbuf());
  try {
    app.parse(int(argv.size()), argv.data());
  } catch (...) {
    std::cout.rdbuf(old);
    throw;
  }
  std::cout.rdbuf(old);
  return captured.str();
}

TEST(InfoCommand, JsonDescribesTheFixtureMesh) {
  nlohmann::json j = nlohmann::json::parse(
      runInfo({io::test::fixturePath("mesh_appended_raw_zlib_h64.vtu"), "--json"}));
  EXPECT_EQ(j["points"], 13);
  EXPECT_EQ(j["tets"], 3);
  EXPECT_EQ(j["pyramids"], 1);
  EXPECT_EQ(j["wedges"], 1);
  EXPECT_EQ(j["hexes"], 1);
  EXPECT_EQ(j["clusters"], 4);
  EXPECT_EQ(j["cellsPerCluster"], (std::vector<int>{1, 2, 2, 1}));
  EXPECT_EQ(j["skipped"]["surface"], 1);
  EXPECT_EQ(j["skipped"]["lineOrVertex"], 1);
  EXPECT_EQ(j["skipped"]["total"], 2);
  EXPECT_EQ(j["quadraticReduced"], 1);
  EXPECT_EQ(j["invertedFixed"], 1);
  EXPECT_EQ(j["bounds"]["lo"], (std::vector<double>{-0.5, -0.5, 0}));
  EXPECT_EQ(j["bounds"]["hi"], (std::vector<double>{1.5, 1.5, 1}));
  EXPECT_EQ(j["timeValues"], (std::vector<double>{0, 0.25, 1}));
  ASSERT_EQ(j["fields"].size(), 4u);
  EXPECT_EQ(j["fields"][2]["name"], "temp");
  EXPECT_EQ(j["fields"][2]["steps"], 3);
  EXPECT_EQ(j["fields"][2]["range"], (std::vector<double>{0, 212}));
  EXPECT_EQ(j["fields"][0]["range"], (std::vector<double>{1, 7}));
  // What each field is read from: a scalar, or a vector shown as its magnitude.
  EXPECT_EQ(j["fields"][0]["components"], 1);
  EXPECT_EQ(j["fields"][1]["name"], "velocity");
  EXPECT_EQ(j["fields"][1]["components"], 3);
}

// The text says a vector renders as its magnitude, and how to render one component. Legacy files
// are not parsed twice to learn it: their components are not known (null).
TEST(InfoCommand, VectorsAreNamedAsMagnitudes) {
  const std::string text = runInfo({io::test::fixturePath("mesh_appended_raw_zlib_h64.vtu")});
  EXPECT_NE(text.find("    velocity: the magnitude of 3 components (velocity[0] .. velocity[2] for "
                      "one), 1 step, range [0, 29.39"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("    pressure: 1 step, range [1, 7]"), std::string::npos) << text;
  nlohmann::json legacy = nlohmann::json::parse(
      runInfo({sm::test::sharedDataPath("notch_stress_fixed.vtk"), "--json"}));
  EXPECT_TRUE(legacy["fields"][0]["components"].is_null());
}

TEST(InfoCommand, FieldAndClusterOptions) {
  const std::string f = io::test::fixturePath("mesh_int_types.vtu");
  nlohmann::json j = nlohmann::json::parse(
      runInfo({"--json", "--field", "big[1]", "--field", "small", "--cluster-array", "part", f}));
  ASSERT_EQ(j["fields"].size(), 2u);
  EXPECT_EQ(j["fields"][0]["name"], "big[1]");
  EXPECT_EQ(j["fields"][0]["components"], 0);  // one component of a vector
  EXPECT_EQ(j["fields"][0]["range"], (std::vector<double>{0, 12}));
  EXPECT_EQ(j["fields"][1]["range"], (std::vector<double>{-12, 0}));
  EXPECT_EQ(j["clusters"], 4);
  j = nlohmann::json::parse(
      runInfo({io::test::fixturePath("weld.pvtu"), "--json", "--pieces", "0,2"}));
  EXPECT_EQ(j["pieces"], 3);
  EXPECT_EQ(j["hexes"], 1);
  EXPECT_EQ(j["tets"], 1);
  EXPECT_EQ(j["clusters"], 3);
  EXPECT_EQ(j["cellsPerCluster"], (std::vector<int>{1, 0, 1}));
}

TEST(InfoCommand, TextNamesEverything) {
  std::string out = runInfo({sm::test::sharedDataPath("notch_stress_fixed.vtk")});
  for (const char* s :
       {"legacy VTK", "points            3537", "hexahedra         2188", "wedges            4",
        "skipped cells     none", "Nodal Stress-0: 1 step, range [", "bounds"})
    EXPECT_NE(out.find(s), std::string::npos) << s << "\n" << out;
}

// Ids far above the cell count are renumbered at load (mesh_builder: per-cluster arrays would
// otherwise be sized by the id), so info lists the one cluster.
TEST(InfoCommand, SparseClusterIdsAreRenumbered) {
  const std::string path = sm::test::outputDir("InfoCommand.Sparse") + "/sparse.vtk";
  io::test::writeText(path,
                      "# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\n"
                      "POINTS 4 float\n0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 3\n"
                      "CELL_TYPES 1\n10\nCELL_DATA 1\nSCALARS cluster int\nLOOKUP_TABLE default\n"
                      "2000000000\n");
  nlohmann::json j = nlohmann::json::parse(runInfo({path, "--json"}));
  EXPECT_EQ(j["clusters"], 1);
  EXPECT_EQ(j["cellsPerCluster"], nlohmann::json::array({1}));
  EXPECT_NE(runInfo({path}).find("clusters          1"), std::string::npos);
}

TEST(InfoCommand, ErrorsAreSmErrors) {
  EXPECT_THROW(runInfo({io::test::fixturePath("mesh_ascii.vtu"), "--cluster-array", "quality"}),
               FileError);
  EXPECT_THROW(runInfo({io::test::fixturePath("mesh_ascii.vtu"), "--field", "nope"}), FileError);
  EXPECT_THROW(runInfo({"/nonexistent/mesh.vtu"}), FileError);
  EXPECT_THROW(runInfo({"mesh.obj"}), Error);
}

}  // namespace
}  // namespace sm::app
