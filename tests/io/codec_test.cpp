#include <gtest/gtest.h>

#include <cstring>
#include <numeric>

#include "common/error.h"
#include "io/base64.h"
#include "io/vtk_binary.h"
#include "io/vtu_arrays.h"
#include "io/vtu_document.h"
#include "io_core/array_plan.h"
#include "io_core/numeric_array.h"
#include "io_core/text_scan.h"
#include "io_test_util.h"

namespace sm::io {
namespace {

std::string decode(std::string_view text, std::vector<size_t> reads) {
  Base64Reader r(text);
  std::string out;
  for (size_t n : reads) {
    std::string part(n, '\0');
    if (!r.read(reinterpret_cast<uint8_t*>(part.data()), n)) return "<short>";
    out += part;
  }
  return out;
}

TEST(Base64, DecodesJointAndSeparatelyPaddedStreams) {
  EXPECT_EQ(decode("TWFu", {3}), "Man");
  EXPECT_EQ(decode("TWE=", {2}), "Ma");
  EXPECT_EQ(decode("TQ==", {1}), "M");
  // VTK encodes a header and its data either as one stream or as two padded ones.
  EXPECT_EQ(decode("TQ==TWE=TWFu", {1, 2, 3}), "MMaMan");
  EXPECT_EQ(decode("TQ==TWE=TWFu", {6}), "MMaMan");
  EXPECT_EQ(decode(" T W\nFu\tTWFu ", {2, 1, 1, 2}), "ManMan");
  EXPECT_EQ(decode("TWFu", {4}), "<short>");
  EXPECT_EQ(decode("TW<u", {3}), "<short>");
  EXPECT_EQ(decode("T===", {1}), "<short>");
}

// Where decoding stopped on a character, the reader says which (messages name it rather than
// calling the data short).
TEST(Base64, NamesTheCharacterThatStoppedIt) {
  auto bad = [](std::string_view text) {
    Base64Reader r(text);
    uint8_t out[6];
    EXPECT_FALSE(r.read(out, 6));
    return r.badCharacter();
  };
  EXPECT_EQ(bad("TWFu"), std::string_view::npos);  // only short
  EXPECT_EQ(bad("TWFu TW<u"), 7u);
  EXPECT_EQ(bad("TWFuT===="), 5u);
  EXPECT_EQ(bad("TWFu=WFu"), 4u);
}

TEST(ZlibBlocks, RoundTripWithPartialAndFullLastBlocks) {
  for (uint64_t bytes : {uint64_t(0), uint64_t(1), uint64_t(4096), uint64_t(10000)}) {
    SCOPED_TRACE(bytes);
    std::vector<uint8_t> raw(bytes);
    std::iota(raw.begin(), raw.end(), uint8_t(7));
    std::vector<uint8_t> enc = compressBlocks(
        bytes, 1024, 1, 0,
        [&](uint64_t b, uint64_t n, uint8_t* dst) { std::memcpy(dst, raw.data() + b, n); });
    PayloadSource src = PayloadSource::raw(enc, 0);
    BinaryFormat f{true, false, Compressor::ZLib, 0};
    Payload p = readPayload(src, f, bytes, "t.vtu", "array");
    ASSERT_TRUE(bytes == 0 || p.data);
    EXPECT_TRUE(bytes == 0 || std::memcmp(p.data, raw.data(), bytes) == 0);
    PayloadSource again = PayloadSource::raw(enc, 0);
    EXPECT_THROW(readPayload(again, f, bytes + 1, "t.vtu", "array"), FileError);
  }
}

// Length::AtLeast takes an array longer than expected whole (VTK reads an array by its own
// length), raw and compressed alike; a shorter one is still refused.
TEST(ZlibBlocks, AnArrayLongerThanExpectedIsReadWholeWhenAllowed) {
  std::vector<uint8_t> raw(3000);
  std::iota(raw.begin(), raw.end(), uint8_t(1));
  std::vector<uint8_t> zlib = compressBlocks(
      raw.size(), 1024, 1, 0,
      [&](uint64_t b, uint64_t n, uint8_t* dst) { std::memcpy(dst, raw.data() + b, n); });
  std::vector<uint8_t> plain(8);
  const uint64_t size = raw.size();
  std::memcpy(plain.data(), &size, 8);
  plain.insert(plain.end(), raw.begin(), raw.end());
  for (Compressor c : {Compressor::None, Compressor::ZLib}) {
    const std::vector<uint8_t>& enc = c == Compressor::ZLib ? zlib : plain;
    const BinaryFormat f{true, false, c, 0};
    PayloadSource longer = PayloadSource::raw(enc, 0);
    Payload p = readPayload(longer, f, 1000, "t.vtu", "array", Length::AtLeast);
    EXPECT_EQ(p.bytes, raw.size());
    EXPECT_EQ(std::memcmp(p.data, raw.data(), raw.size()), 0);
    PayloadSource exact = PayloadSource::raw(enc, 0);
    EXPECT_THROW(readPayload(exact, f, 1000, "t.vtu", "array"), FileError);
    PayloadSource shorter = PayloadSource::raw(enc, 0);
    EXPECT_THROW(readPayload(shorter, f, 3001, "t.vtu", "array", Length::AtLeast), FileError);
  }
}

// The same through a document, in every encoding: a DataArray asked for with fewer tuples than it
// holds comes back whole.
TEST(VtuDocument, DecodesAtLeastTheTuplesAsked) {
  for (const char* name : {"mesh_ascii.vtu", "mesh_binary_zlib_h32.vtu",
                           "mesh_appended_raw_none_h64.vtu", "mesh_binary_none_h32.vtu"}) {
    SCOPED_TRACE(name);
    const std::string path = test::fixturePath(name);
    FileBytes bytes = FileBytes::openLazily(path);
    VtuDocument doc(bytes, path, "UnstructuredGrid");
    const pugi::xml_node ids =
        findDataArray(vtuPieces(doc).at(0).node.child("Cells"), "connectivity");
    const NumericArray all = doc.decode(ids, 1, "connectivity", 1, Length::AtLeast);
    ASSERT_GT(all.tuples, 1u);
    EXPECT_EQ(toInt64(doc.decode(ids, all.tuples, "connectivity", 1), path, "c"),
              toInt64(all, path, "c"));
    EXPECT_THROW(doc.decode(ids, 1, "connectivity", 1), FileError);
    EXPECT_THROW(doc.decode(ids, all.tuples + 1, "connectivity", 1, Length::AtLeast), FileError);
  }
}

TEST(ZlibBlocks, CorruptBlockIsAFileError) {
  std::vector<uint8_t> raw(5000, 3);
  std::vector<uint8_t> enc = compressBlocks(
      raw.size(), 1024, 1, 0,
      [&](uint64_t b, uint64_t n, uint8_t* dst) { std::memcpy(dst, raw.data() + b, n); });
  enc[enc.size() - 3] ^= 0x55;
  PayloadSource src = PayloadSource::raw(enc, 0);
  try {
    readPayload(src, {true, false, Compressor::ZLib, 0}, raw.size(), "t.vtu", "array 'x'");
    FAIL();
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("t.vtu: array 'x': compressed block 4 is corrupt"),
              std::string::npos)
        << e.what();
  }
}

TEST(TextScan, NumbersAsWritersWriteThem) {
  double d = 0;
  EXPECT_TRUE(parseNumber("+1.5", d));
  EXPECT_EQ(d, 1.5);
  EXPECT_TRUE(parseNumber("1.5D+03", d));  // Fortran
  EXPECT_EQ(d, 1500.0);
  EXPECT_TRUE(parseNumber("-nan", d));
  EXPECT_TRUE(d != d);
  EXPECT_FALSE(parseNumber("12x", d));
  EXPECT_FALSE(parseNumber("", d));
  int64_t i = 0;
  EXPECT_FALSE(parseNumber("1.0", i));
  EXPECT_TRUE(parseNumber("-42", i));
  EXPECT_EQ(i, -42);
  EXPECT_EQ(printable(std::string_view("a\0b\n", 4)), "a?b?");
}

TEST(ArrayPlan, TimeStepNames) {
  EXPECT_EQ(splitStepName("p@t3").base, "p");
  EXPECT_EQ(splitStepName("p@t3").step, 3u);
  EXPECT_EQ(splitStepName("p@t0").step, 0u);
  EXPECT_EQ(splitStepName("p@t10").step, 10u);
  for (const char* plain : {"p", "p@t", "p@tx", "@t1", "p@t-1", "p@t+1", "p@t1x", "p@t01", "p@t00"})
    EXPECT_FALSE(splitStepName(plain).step) << plain;
}

TEST(ArrayPlan, PlainAndSteppedNamesMayNotClash) {
  ReadOptions o;
  EXPECT_THROW(planFields("f.vtu", {{"p", 1, false}, {"p@t0", 1, false}}, o), FileError);
  EXPECT_THROW(planFields("f.vtu", {{"p@t0", 1, false}, {"p@t0", 1, false}}, o), FileError);
  EXPECT_THROW(planFields("f.vtu", {{"p@t0", 1, false}, {"p@t1", 3, false}}, o), FileError);
  auto loads = planFields("f.vtu", {{"p@t1", 1, false}, {"id", 1, true}, {"p@t0", 1, false}}, o);
  ASSERT_EQ(loads.size(), 2u);  // identifiers only when asked for
  EXPECT_EQ(loads[0].array, 2u);
  EXPECT_EQ(loads[0].step, 0u);
  EXPECT_EQ(loads[1].step, 1u);
}

// A step number comes from a name: a gap, or one far beyond the number of arrays, is a missing
// step, found before any field is sized (a fuzzer's "p@t<huge>" asked for exabytes).
TEST(ArrayPlan, MissingOrHugeStepsAreErrorsBeforeAnythingIsSized) {
  ReadOptions o;
  for (const char* name : {"p@t2", "p@t18446744073709551615", "p@t1234567890123"}) {
    try {
      planFields("f.vtu", {{"p@t0", 1, false}, {name, 1, false}}, o);
      ADD_FAILURE() << name << " accepted";
    } catch (const FileError& e) {
      EXPECT_NE(std::string(e.what()).find("has no values for time step 1"), std::string::npos)
          << e.what();
    }
  }
  o.step = 0;  // --time: the same check
  EXPECT_THROW(planFields("f.vtu", {{"p@t0", 1, false}, {"p@t5", 1, false}}, o), FileError);
}

// 1e12 + 0..1000 stored as int64 all become 999999995904 in float: a warning says so, once per
// array; a span floats resolve, a constant array and float input say nothing.
TEST(ToFloats, WarnsOnceWhenFloatsCannotResolveTheValues) {
  std::vector<int64_t> big(11);
  for (size_t i = 0; i < big.size(); ++i) big[i] = 1000000000000 + int64_t(100 * i);
  auto view = [](ScalarType t, const auto& v) {
    return NumericArray::view(t, 1, v.size(), reinterpret_cast<const uint8_t*>(v.data()), false);
  };
  const ArrayName step0{"a.vtu", "point", "big@t0"}, step1{"b.vtu", "point", "big@t1"};
  testing::internal::CaptureStderr();
  std::vector<float> f = toFloats(view(ScalarType::Int64, big), -1, 1, &step0);
  toFloats(view(ScalarType::Int64, big), -1, 1, &step1);  // another piece's, or step's: said once
  const std::string warned = testing::internal::GetCapturedStderr();
  EXPECT_EQ(f.front(), f.back());
  EXPECT_NE(warned.find("a.vtu: point array 'big@t0': values span 1000 at 1e+12, where 32-bit "
                        "floats step by 65536: they show as one value"),
            std::string::npos)
      << warned;
  EXPECT_EQ(warned.find("point array"), warned.rfind("point array")) << warned;
  const std::vector<double> fine = {101325.0, 101325.5, 101400.0}, flat = {7.0, 7.0};
  const std::vector<float> floats = {1e12f, 1e12f + 65536.0f};
  const ArrayName p{"a.vtu", "point", "p"}, c{"a.vtu", "point", "c"}, fl{"a.vtu", "point", "f"};
  testing::internal::CaptureStderr();
  toFloats(view(ScalarType::Float64, fine), -1, 1, &p);
  toFloats(view(ScalarType::Float64, flat), -1, 1, &c);
  toFloats(view(ScalarType::Float32, floats), -1, 1, &fl);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  // A few levels left: said with their count. 1e6 + 0..0.25 in steps of 1/16 (floats' there).
  const std::vector<double> few = {1e6, 1e6 + 0.125, 1e6 + 0.25};
  const ArrayName q{"a.vtu", "cell", "q"};
  testing::internal::CaptureStderr();
  toFloats(view(ScalarType::Float64, few), -1, 1, &q);
  const std::string levels = testing::internal::GetCapturedStderr();
  EXPECT_NE(levels.find("a.vtu: cell array 'q': values span 0.25 at 1e+06, where 32-bit floats "
                        "step by 0.0625: at most 5 levels show"),
            std::string::npos)
      << levels;
}

}  // namespace
}  // namespace sm::io
