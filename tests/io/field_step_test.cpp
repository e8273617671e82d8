// One time step read on its own (io::readFieldStep, io::listFieldSteps, ReadOptions::step): the
// same values, in the same point order, as readMesh gives, for every .vtu encoding and for welded
// .pvtu pieces; errors name the file and the array.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "io/mesh_io.h"
#include "io_test_util.h"
#include "support/test_support.h"

namespace sm::io {
namespace {

namespace fs = std::filesystem;
using test::fileErrorOf;
using test::fixturePath;

// Every step of every field of `path` read on its own equals readMesh's.
void expectStepsLikeReadMesh(const std::string& path, const ReadOptions& o = {}) {
  SCOPED_TRACE(path);
  const mesh::UnstructuredMesh m = readMesh(path, o);
  ASSERT_FALSE(m.fields.empty());
  const std::vector<FieldStepCount> listed = listFieldSteps(path, o);
  ASSERT_EQ(listed.size(), m.fields.size());
  for (size_t f = 0; f < m.fields.size(); ++f) {
    const mesh::Field& field = m.fields[f];
    EXPECT_EQ(listed[f].name, field.name);
    EXPECT_EQ(listed[f].steps, field.numSteps()) << field.name;
    for (uint64_t s = 0; s < field.numSteps(); ++s) {
      std::vector<float> v = readFieldStep(path, field.name, s, o, m.pointOrigin);
      ASSERT_EQ(v.size(), m.numPoints());
      // Bitwise (NaN included): the same conversion of the same bytes.
      EXPECT_EQ(std::memcmp(v.data(), field.steps[s].data(), v.size() * sizeof(float)), 0)
          << field.name << " step " << s;
    }
  }
}

TEST(FieldStep, EveryVtuEncodingGivesReadMeshValues) {
  for (const char* file : {"mesh_ascii.vtu", "mesh_binary_none_h32.vtu", "mesh_binary_zlib_h64.vtu",
                           "mesh_binary_zlib_bigendian.vtu", "mesh_appended_raw_none_h64.vtu",
                           "mesh_appended_raw_zlib_h32.vtu", "mesh_appended_b64_zlib_h64.vtu",
                           "mesh_appended_raw_none_bigendian.vtu", "mesh_int_types.vtu"})
    expectStepsLikeReadMesh(fixturePath(file));
}

TEST(FieldStep, ComponentsAndLegacyFilesToo) {
  ReadOptions o;
  o.fields = {"velocity[1]", "temp"};
  expectStepsLikeReadMesh(fixturePath("mesh_binary_zlib_h32.vtu"), o);
  expectStepsLikeReadMesh(fixturePath("mesh_v51_binary.vtk"));  // read whole, same answer
}

TEST(FieldStep, WeldedPvtuPiecesFollowTheWeldedPoints) {
  expectStepsLikeReadMesh(fixturePath("weld.pvtu"));
  const mesh::UnstructuredMesh m = readMesh(fixturePath("weld.pvtu"));
  EXPECT_LT(m.numPoints(), 8u + 9u + 4u);  // points were merged, so the origins matter
  const std::string dir = sm::test::outputDir("FieldStep.Pvtu");
  const mesh::UnstructuredMesh big = test::makeTestMesh(5, 4);
  writePvtu(dir + "/slabs.pvtu", big, {false, 1});
  expectStepsLikeReadMesh(dir + "/slabs.pvtu");
  ReadOptions some;
  some.pieces = {3, 1, 2};
  expectStepsLikeReadMesh(dir + "/slabs.pvtu", some);
}

TEST(FieldStep, LoadingOneStepKeepsOnlyThatStep) {
  const std::string dir = sm::test::outputDir("FieldStep.OneStep");
  writePvtu(dir + "/m.pvtu", test::makeTestMesh(3, 2));
  const mesh::UnstructuredMesh all = readMesh(dir + "/m.pvtu");
  for (uint64_t step : {0, 1, 7}) {
    ReadOptions o;
    o.step = step;
    const mesh::UnstructuredMesh one = readMesh(dir + "/m.pvtu", o);
    EXPECT_EQ(one.points, all.points);
    EXPECT_EQ(one.pointOrigin, all.pointOrigin);
    ASSERT_EQ(one.fields.size(), all.fields.size());
    for (size_t f = 0; f < all.fields.size(); ++f) {
      ASSERT_EQ(one.fields[f].numSteps(), 1u) << all.fields[f].name;
      const uint64_t held = std::min(step, all.fields[f].numSteps() - 1);  // fewer steps: the last
      EXPECT_EQ(one.fields[f].steps[0], all.fields[f].steps[held]) << all.fields[f].name;
    }
  }
}

TEST(FieldStep, PointsAndCellsAreNotDecoded) {
  const std::string dir = sm::test::outputDir("FieldStep.NotDecoded");
  const mesh::UnstructuredMesh m = test::makeTestMesh(3, 1);
  const std::string path = dir + "/raw.vtu";
  writeVtu(path, m, {false, 1});
  const std::vector<float> before = readFieldStep(path, "g", 1);
  // Give the points array an impossible byte count: readMesh must fail, the field still reads.
  std::vector<uint8_t> bytes = test::readBytes(path);
  const std::string text(bytes.begin(), bytes.end());
  const size_t points = text.find("offset=\"", text.find("<Points>")) + 8;
  const size_t data = text.find('_', text.find("<AppendedData")) + 1;
  const uint64_t huge = uint64_t(1) << 50;
  std::memcpy(&bytes[data + std::stoull(text.substr(points))], &huge, sizeof huge);
  test::writeBytes(path, bytes);
  EXPECT_NE(fileErrorOf([&] { readMesh(path); }), "");
  EXPECT_EQ(readFieldStep(path, "g", 1), before);
}

TEST(FieldStep, MissingStepsArraysAndTruncatedDataAreNamed) {
  const std::string dir = sm::test::outputDir("FieldStep.Errors");
  const std::string path = dir + "/m.vtu";
  writeVtu(path, test::makeTestMesh(3, 1), {false, 1});
  std::string msg = fileErrorOf([&] { readFieldStep(path, "g", 2); });
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find("g@t2"), std::string::npos) << msg;
  msg = fileErrorOf([&] { readFieldStep(path, "nope", 0); });
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find("'nope'"), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  msg = fileErrorOf([&] { readFieldStep(dir + "/absent.vtu", "g", 0); });
  EXPECT_NE(msg.find("absent.vtu"), std::string::npos) << msg;

  // Cut the file inside the data of g@t1: that step fails naming its array.
  std::vector<uint8_t> bytes = test::readBytes(path);
  const std::string text(bytes.begin(), bytes.end());
  const size_t array = text.find("offset=\"", text.find("Name=\"g@t1\"")) + 8;
  const size_t data = text.find('_', text.find("<AppendedData")) + 1;
  bytes.resize(data + std::stoull(text.substr(array)) + 8 + 12);
  const std::string cut = dir + "/cut.vtu";
  test::writeBytes(cut, bytes);
  msg = fileErrorOf([&] { readFieldStep(cut, "g", 1); });
  EXPECT_NE(msg.find(cut), std::string::npos) << msg;
  EXPECT_NE(msg.find("point array 'g@t1'"), std::string::npos) << msg;
}

// Ranks read their own pieces; when the pieces of one read disagree on a field's steps, the read
// fails as the weld of a full read does, even when only one step is loaded.
TEST(FieldStep, PiecesWithDifferentStepCounts) {
  const std::string dir = sm::test::outputDir("FieldStep.Differ");
  mesh::UnstructuredMesh m = test::makeTestMesh(3, 2);
  fs::create_directories(dir + "/two");
  fs::create_directories(dir + "/three");
  writePvtu(dir + "/two/m.pvtu", m);
  for (mesh::Field& f : m.fields) f.steps.push_back(f.steps.back());  // one more step each
  writePvtu(dir + "/three/m.pvtu", m);
  fs::copy_file(dir + "/three/m/m_1.vtu", dir + "/two/m/m_1.vtu",
                fs::copy_options::overwrite_existing);
  const std::string path = dir + "/two/m.pvtu";
  ReadOptions o;
  o.step = 0;
  std::string msg = fileErrorOf([&] { readMesh(path, o); });
  EXPECT_NE(msg.find("m_1.vtu"), std::string::npos) << msg;
  EXPECT_NE(msg.find("time steps"), std::string::npos) << msg;
  EXPECT_NE(fileErrorOf([&] { listFieldSteps(path); }).find("m_1.vtu"), std::string::npos);
  o.pieces = {1};
  EXPECT_EQ(listFieldSteps(path, o).at(1).steps, 3u);
  o.pieces = {0};
  EXPECT_EQ(listFieldSteps(path, o).at(1).steps, 2u);
}

}  // namespace
}  // namespace sm::io
