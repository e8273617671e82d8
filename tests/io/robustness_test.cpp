// Other people's files: truncated, corrupted, or declaring absurd sizes. Every reader must answer
// with a mesh or one sm::FileError naming the input, never crash, hang, or allocate what the file
// merely claims. A replaced global operator new (plain and aligned) enforces the last point: while
// a limit is set, a larger request throws std::bad_alloc, which these tests count as a failure.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <new>
#include <random>
#include <string>

#include "common/log.h"
#include "io/mesh_io.h"
#include "io_test_util.h"
#include "support/allocation_cap.h"
#include "support/test_support.h"

namespace sm::io {
namespace {

using test::fixturePath;

using Guard = sm::test::AllocationCap;

// Reads bytes as `name`; returns "" for a mesh, the message for a FileError; fails otherwise.
std::string outcome(const std::vector<uint8_t>& bytes, const std::string& name) {
  try {
    readMeshFromMemory(bytes, name);
    return "";
  } catch (const FileError& e) {
    std::string msg = e.what();
    EXPECT_EQ(msg.rfind(name, 0), 0u) << "the message must start with the input's name: " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
    return msg.empty() ? "?" : msg;
  } catch (const std::bad_alloc&) {
    ADD_FAILURE() << name << ": allocation beyond the limit (the reader believed a size)";
  } catch (const std::exception& e) {
    ADD_FAILURE() << name << ": not a FileError: " << e.what();
  }
  return "?";
}

const char* kFiles[] = {"mesh_ascii.vtu",
                        "mesh_binary_none_h32.vtu",
                        "mesh_binary_zlib_h64.vtu",
                        "mesh_appended_raw_none_h64.vtu",
                        "mesh_appended_raw_zlib_h32.vtu",
                        "mesh_appended_b64_zlib_h64.vtu",
                        "mesh_appended_b64_none_h32.vtu",
                        "mesh_binary_zlib_bigendian.vtu",
                        "mesh_lz4.vtu",
                        "mesh_lzma.vtu",
                        "mesh_int_types.vtu",
                        "mesh_v42_ascii.vtk",
                        "mesh_v42_binary.vtk",
                        "mesh_v51_ascii.vtk",
                        "mesh_v51_binary.vtk"};

TEST(Robustness, TruncatedFilesAreErrorsNotCrashes) {
  Guard guard;
  for (const char* f : kFiles) {
    const std::vector<uint8_t> full = test::readBytes(fixturePath(f));
    ASSERT_FALSE(full.empty()) << f;
    int errors = 0;
    for (size_t cut = 0; cut < full.size(); cut += 1 + full.size() / 97) {
      std::vector<uint8_t> part(full.begin(), full.begin() + cut);
      errors += !outcome(part, f).empty();
    }
    // Most cuts lose data. Some leave a valid shorter file: inside closing tags, or (legacy)
    // between sections, which may legally be absent.
    EXPECT_GT(errors, 60) << f;
  }
}

TEST(Robustness, FlippedBytesAreErrorsOrMeshes) {
  Guard guard;
  std::mt19937 rng(12345);
  for (const char* f : kFiles) {
    const std::vector<uint8_t> full = test::readBytes(fixturePath(f));
    for (int trial = 0; trial < 300; ++trial) {
      std::vector<uint8_t> bytes = full;
      for (int k = 0; k < 1 + trial % 3; ++k)
        bytes[rng() % bytes.size()] ^= static_cast<uint8_t>(1u << (rng() % 8));
      outcome(bytes, f);
    }
  }
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::vector<uint8_t> bytesOf(const std::string& s) {
  return {s.begin(), s.end()};
}

std::string fixtureText(const char* f) {
  std::vector<uint8_t> b = test::readBytes(fixturePath(f));
  return {b.begin(), b.end()};
}

void expectError(const std::string& text, const std::string& name, const std::string& part) {
  std::string msg = outcome(bytesOf(text), name);
  EXPECT_NE(msg.find(part), std::string::npos) << "expected '" << part << "' in: " << msg;
}

TEST(Robustness, AbsurdSizesInVtuAreRejectedBeforeAllocating) {
  Guard guard;
  const std::string ascii = fixtureText("mesh_ascii.vtu");
  expectError(replaced(ascii, "NumberOfCells=\"8\"", "NumberOfCells=\"1099511627776\""), "a.vtu",
              "declares 1099511627776 values");
  expectError(replaced(ascii, "NumberOfCells=\"8\"", "NumberOfCells=\"1152921504606846975\""),
              "a.vtu", "impossible size");
  expectError(replaced(ascii, "NumberOfPoints=\"13\"", "NumberOfPoints=\"-5\""), "a.vtu",
              "not a count");
  const std::string raw = fixtureText("mesh_appended_raw_none_h64.vtu");
  expectError(replaced(raw, "NumberOfPoints=\"13\"", "NumberOfPoints=\"4294967295\""), "r.vtu",
              "holds 312 bytes, expected 103079215080");
  expectError(replaced(raw, "NumberOfCells=\"8\"", "NumberOfCells=\"100000000\""), "r.vtu",
              "expected 800000000");
  // An appended array whose header claims more bytes than the file has.
  std::string huge = raw;
  const size_t data = huge.find('_', huge.find("<AppendedData")) + 1;
  const uint64_t claim = uint64_t(1) << 40;
  std::memcpy(&huge[data], &claim, 8);  // first array: the field data TimeValues
  expectError(huge, "r.vtu", "holds 1099511627776 bytes, expected 24");
  const std::string zlib = fixtureText("mesh_appended_raw_zlib_h64.vtu");
  std::string blocks = zlib;
  const size_t zdata = blocks.find('_', blocks.find("<AppendedData")) + 1;
  std::memcpy(&blocks[zdata], &claim, 8);  // number of blocks
  expectError(blocks, "z.vtu", "more than the data can hold");
}

TEST(Robustness, BrokenStructureInVtu) {
  Guard guard;
  const std::string ascii = fixtureText("mesh_ascii.vtu");
  expectError(replaced(ascii, "<VTKFile", "<VTKFil"), "a.vtu", "not valid XML");
  expectError(replaced(ascii, "type=\"UnstructuredGrid\"", "type=\"PolyData\""), "a.vtu",
              "'PolyData'");
  expectError(
      replaced(ascii, "type=\"Float64\" Name=\"Points\"", "type=\"Float128\" Name=\"Points\""),
      "a.vtu", "unsupported array type 'Float128'");
  expectError(replaced(ascii, "Name=\"Points\" NumberOfComponents=\"3\"",
                       "Name=\"Points\" NumberOfComponents=\"2\""),
              "a.vtu", "has 2 components, expected 3");
  expectError(replaced(ascii, "8 13 19", "8 3 19"), "a.vtu", "smaller than the one before");
  expectError(replaced(ascii, "0.5 -0.5 0.5", "0.5 -0.5 nan"), "a.vtu", "non-finite");
  expectError(replaced(ascii, "0.5 -0.5 0.5", "0.5 -0.5 0.5x"), "a.vtu",
              "('0.5x') is not a number");
  expectError(replaced(ascii, "format=\"ascii\"", "format=\"appended\""), "a.vtu",
              "refers to appended data, but there is none");
  // A connectivity id beyond the points.
  expectError(replaced(ascii, "6 7 1 2 6 5", "6 70 1 2 6 5"), "a.vtu", "refers to point 70");
  // A word among XML values is just not a number (no section keyword to blame, unlike legacy).
  expectError(replaced(ascii, "6 7 1 2 6 5", "6 abc 1 2 6 5"), "a.vtu",
              "('abc') is not a whole number");
  const std::string b64 = fixtureText("mesh_binary_zlib_h32.vtu");
  expectError(
      replaced(b64, "compressor=\"vtkZLibDataCompressor\"", "compressor=\"vtkZstdDataCompressor\""),
      "b.vtu", "unknown compressor");
  expectError(replaced(b64, "header_type=\"UInt32\"", "header_type=\"UInt16\""), "b.vtu",
              "header_type");
  // A damaged character is named where it is, not taken for the end of the data.
  expectError(replaced(b64, "AQAAAIAAAAA0AAAALgAAAA==", "AQ#AAIAAAAA0AAAALgAAAA=="), "b.vtu",
              "point array 'pressure': '#', not base64, at character 13 of its base64 text");
  expectError(replaced(b64, "AQAAAIAAAAA0AAAALgAAAA==", "AQAAA=AAAAA0AAAALgAAAA=="), "b.vtu",
              "padding '=' out of place at character 16");
  // Appended base64: counted from the array's own offset, not from the appended data's start.
  expectError(
      replaced(fixtureText("mesh_appended_b64_none_h32.vtu"), "==NAAAAAAAgD8A", "==NA#AAAAAgD8A"),
      "c.vtu", "point array 'pressure': '#', not base64, at character 2 of its base64 text");
}

// LZ4 (appended raw) and LZMA (inline base64) blocks of the point coordinates (3 blocks: 128,
// 128 and 56 bytes), damaged: a byte of a block, and the header's block sizes changed so that
// they still add up to the array's 312 bytes but no longer match what each block decodes to.
TEST(Robustness, DamagedLz4AndLzmaBlocks) {
  Guard guard;
  const std::string lz4 = fixtureText("mesh_lz4.vtu");
  const size_t points = lz4.find('_', lz4.find("<AppendedData")) + 1 + 864;  // its offset
  const std::string what = "points: compressed block 0 is corrupt (";
  std::string byte = lz4;
  byte[points + 48] ^= 0x55;  // block 0's first token
  expectError(byte, "l.vtu", what + "lz4: ");
  std::string sizes = lz4;
  const uint64_t blockSize = 130, lastSize = 52;
  std::memcpy(&sizes[points + 8], &blockSize, 8);
  std::memcpy(&sizes[points + 16], &lastSize, 8);
  expectError(sizes, "l.vtu", what + "lz4: wrong size)");

  const std::string lzma = fixtureText("mesh_lzma.vtu");
  expectError(replaced(lzma, "bhU3xBexvf1x", "bhU3xBeyvf1x"), "x.vtu", what + "lzma: data error)");
  expectError(replaced(lzma, "AwAAAAAAAACAAAAAAAAAADgAAAAAAAAAVAAAAAAAAABYAAAAAAAAAEgAAAAAAAAA",
                       "AwAAAAAAAACCAAAAAAAAADQAAAAAAAAAVAAAAAAAAABYAAAAAAAAAEgAAAAAAAAA"),
              "x.vtu", what + "lzma: wrong size (its index records 128 bytes))");
}

TEST(Robustness, AbsurdSizesInLegacyVtk) {
  Guard guard;
  const std::string ascii = fixtureText("mesh_v42_ascii.vtk");
  expectError(replaced(ascii, "POINTS 13 double", "POINTS 4294967295 double"), "a.vtk",
              "too short");
  expectError(replaced(ascii, "CELLS 8 49", "CELLS 8 1099511627776"), "a.vtk", "too short");
  // A count one off names the section and what was found instead of its values.
  expectError(replaced(ascii, "CELL_TYPES 8", "CELL_TYPES 9"), "a.vtk",
              "cell types: found 'CELL_DATA' after 8 of the 9 values its header declares");
  expectError(replaced(ascii, "CELL_TYPES 8", "CELL_TYPES 7"), "a.vtk",
              "found the number '1' where a keyword should be: the CELL_TYPES section holds more "
              "values than it declares");
  expectError(replaced(ascii, "CELLS 8 49", "CELLS 8 50"), "a.vtk",
              "cells: found 'CELL_TYPES' after 49 of the 50 values");
  expectError(replaced(ascii, "CELLS 8 49", "CELLS 8 48"), "a.vtk",
              "where a keyword should be: the CELLS section holds more values");
  // Also in an array that is skipped rather than read (cell data no --field names).
  expectError(replaced(ascii, "0.85714285714 1", "0.85714285714"), "a.vtk",
              "cell array 'quality': found 'METADATA' after 7 of the 8 values");
  // A value too many in an array names the array, not the FIELD or SCALARS section around it.
  expectError(replaced(ascii, "0.85714285714 1 \n", "0.85714285714 1 2\n"), "a.vtk",
              "found the number '2' where a keyword should be: cell array 'quality' holds more "
              "values than it declares");
  expectError(replaced(ascii, "0 0.25 1 \n", "0 0.25 1 7\n"), "a.vtk",
              "found the number '7' where a keyword should be: field data 'TimeValues' holds");
  expectError(replaced(ascii, "5.5 6 6.5 7 \n", "5.5 6 6.5 7 8\n"), "a.vtk",
              "found the number '8' where a keyword should be: point array 'pressure' holds");
  // Within a FIELD of two arrays the extra value stands where the next array's name should.
  expectError(
      replaced(replaced(ascii, "FIELD FieldData 1\nquality", "FIELD FieldData 2\nquality"),
               "0.85714285714 1 \n", "0.85714285714 1 9\nother 1 8 double\n1 2 3 4 5 6 7 8\n"),
      "a.vtk",
      "FIELD: found the number '9' where array 1's name should be: cell array 'quality' "
      "holds more values than it declares");
  expectError(replaced(ascii, "4 0 4 1 12", "4 0 4 1 13"), "a.vtk", "refers to point 13");
  expectError(replaced(ascii, "CELLS 8 49", "CELLS 9 49"), "a.vtk",
              "CELL_DATA 8 does not match the 9 cells");
  expectError(replaced(ascii, "POINT_DATA 13", "POINT_DATA 12"), "a.vtk",
              "does not match the 13 points");
  const std::string bin = fixtureText("mesh_v51_binary.vtk");
  expectError(replaced(bin, "POINTS 13 double", "POINTS 4611686018427387904 double"), "b.vtk",
              "not a count");
  expectError(replaced(bin, "POINTS 13 double", "POINTS 4294967295 double"), "b.vtk", "needs");
  expectError(replaced(bin, "CELLS 9 41", "CELLS 1000000000 41"), "b.vtk", "file ends");
  expectError(replaced(bin, "vtktypeint64", "vtktypeint128"), "b.vtk", "unknown data type");
}

// Vertex ids are 32-bit: a file declaring 2^32 points or more is refused by its header alone, with
// one line naming the limit and what would fit; 2^32 - 1 passes that check and fails only on the
// data the file lacks (read against the file's size, never allocated).
TEST(Robustness, PointCountsPast32BitIdsAreRefusedBeforeReading) {
  Guard guard;
  const std::string limit = "points: vertex ids are 32-bit, so one mesh holds at most 4294967295";
  const std::string raw = fixtureText("mesh_appended_raw_none_h64.vtu");
  expectError(replaced(raw, "NumberOfPoints=\"13\"", "NumberOfPoints=\"4294967296\""), "r.vtu",
              "r.vtu: declares 4294967296 " + limit);
  expectError(replaced(raw, "NumberOfPoints=\"13\"", "NumberOfPoints=\"4294967296\""), "r.vtu",
              "use more ranks");
  const std::string ascii = fixtureText("mesh_ascii.vtu");
  expectError(replaced(ascii, "NumberOfPoints=\"13\"", "NumberOfPoints=\"1152921504606846975\""),
              "a.vtu", "declares 1152921504606846975 " + limit);
  // Pieces of one .vtu count together (their ids are numbered one after another).
  const size_t begin = ascii.find("<Piece"), end = ascii.find("</Piece>") + 8;
  const std::string piece = ascii.substr(begin, end - begin);
  auto twoPieces = [&](const std::string& secondPoints) {
    std::string text = ascii;
    text.insert(
        end, replaced(piece, "NumberOfPoints=\"13\"", "NumberOfPoints=\"" + secondPoints + "\""));
    return text;
  };
  expectError(twoPieces("4294967283"), "p.vtu", "its pieces declare 4294967296 " + limit);
  expectError(twoPieces("4294967282"), "p.vtu", "declares 12884901846 values but its text");
  const std::string vtk = fixtureText("mesh_v51_binary.vtk");
  expectError(replaced(vtk, "POINTS 13 double", "POINTS 4294967296 double"), "b.vtk",
              "b.vtk: declares 4294967296 " + limit);
  const std::string vtkAscii = fixtureText("mesh_v42_ascii.vtk");
  expectError(replaced(vtkAscii, "POINTS 13 double", "POINTS 4294967296 double"), "a.vtk",
              "a.vtk: declares 4294967296 " + limit);
}

// Cell counts are 64-bit throughout the readers: past 2^31 and 2^32 a header is believed only as
// far as the file's data goes (no int or uint32 wraps into a small, plausible count). Cell origins
// are 32-bit: asked for (streamed cell data), 2^32 cells are refused before anything is read.
TEST(Robustness, CellCountsPast2To31And2To32AreCheckedAgainstTheData) {
  Guard guard;
  const std::string ascii = fixtureText("mesh_ascii.vtu");
  expectError(replaced(ascii, "NumberOfCells=\"8\"", "NumberOfCells=\"2147483649\""), "a.vtu",
              "cell offsets: declares 2147483649 values");
  const std::string raw = fixtureText("mesh_appended_raw_none_h64.vtu");
  expectError(replaced(raw, "NumberOfCells=\"8\"", "NumberOfCells=\"4294967297\""), "r.vtu",
              "expected 34359738376");
  const std::string vtk = fixtureText("mesh_v51_binary.vtk");
  expectError(replaced(vtk, "CELLS 9 41", "CELLS 4294967298 41"), "b.vtk", "file ends");
  ReadOptions origins;
  origins.cellOrigins = true;
  const std::string text = replaced(raw, "NumberOfCells=\"8\"", "NumberOfCells=\"4294967296\"");
  const std::string msg =
      test::fileErrorOf([&] { readMeshFromMemory(bytesOf(text), "r.vtu", origins); });
  EXPECT_EQ(msg.rfind("r.vtu: has 4294967296 cells: cell origins are 32-bit", 0), 0u) << msg;
  EXPECT_NE(msg.find("use more ranks"), std::string::npos) << msg;
}

// A FIFO opens for reading only once a writer comes: as a mesh, a piece or a piece sized from its
// header it must be refused at once, not waited on (a hang on a cluster's shared file system).
TEST(Robustness, PipesAndFoldersAreRefusedNotWaitedOn) {
  const std::string dir = sm::test::outputDir("Robustness.Pipes");
  const std::string fifo = dir + "/fifo.vtu";
  std::filesystem::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::filesystem::create_directories(dir + "/folder.vtu");
  std::filesystem::copy_file(fixturePath("mesh_ascii.vtu"), dir + "/ok.vtu",
                             std::filesystem::copy_options::overwrite_existing);
  for (const char* piece : {"fifo.vtu", "folder.vtu"}) {
    const std::string index = dir + "/with_" + std::string(piece, 4) + ".pvtu";
    test::writeText(
        index,
        std::string(
            R"(<?xml version="1.0"?><VTKFile type="PUnstructuredGrid" version="1.0"><PUnstructuredGrid><Piece Source="ok.vtu"/><Piece Source=")") +
            piece + R"("/></PUnstructuredGrid></VTKFile>)");
    const std::string want = dir + "/" + piece + ": not a regular file";
    EXPECT_EQ(test::fileErrorOf([&] { readMesh(index); }), want);
    EXPECT_EQ(test::fileErrorOf([&] { pieceCellCounts(index); }), want);
    EXPECT_EQ(test::fileErrorOf([&] { readMesh(dir + "/" + piece); }), want);
  }
}

TEST(Robustness, AbsurdSizesInUgrid) {
  Guard guard;
  expectError("1099511627776 0 0 1 0 0 0\n0 0 0\n", "a.ugrid", "declares 1099511627776 nodes");
  expectError("4 0 0 1 0 0 0\n0 0 0 1 0 0 0 1 0 0 0 1\n1 2 3 5\n", "a.ugrid", "refers to node 5");
  expectError("4 0 0 1 0 0 0\n0 0 0 1 0 0 0 1 0 0 0 1\n1 2 3\n", "a.ugrid", "ends after 3 of 4");
  std::vector<uint8_t> bin(28, 0);
  const int32_t counts[7] = {1 << 30, 0, 0, 1 << 30, 0, 0, 0};
  std::memcpy(bin.data(), counts, 28);
  std::string msg = outcome(bin, "b.lb8.ugrid");
  EXPECT_NE(msg.find("impossible for a file of 28 bytes"), std::string::npos) << msg;
  const int32_t fits[7] = {4, 0, 0, 1, 0, 0, 0};  // counts fit, data missing
  std::memcpy(bin.data(), fits, 28);
  msg = outcome(bin, "b.lb8.ugrid");
  EXPECT_NE(msg.find("need 112 bytes; the file has 0"), std::string::npos) << msg;
  EXPECT_NE(outcome({}, "e.lb8.ugrid").find("too short"), std::string::npos);
  EXPECT_NE(outcome({}, "e.vtu").find("e.vtu"), std::string::npos);
  EXPECT_NE(outcome({}, "e.vtk").find("not a legacy VTK file"), std::string::npos);
}

}  // namespace
}  // namespace sm::io
