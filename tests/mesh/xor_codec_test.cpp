// Round trip of the XOR compaction for every element type, from every possible entry face, in
// every rotation of the face, for both the full face and (where the shell supplies only one
// triangle of a split quad) three consecutive quad vertices.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include "mesh/cell_type.h"
#include "shared/xor_codec.h"

namespace sm::mesh {
namespace {

using gpu::uint;

std::vector<uint> randomIds(std::mt19937& rng, uint n) {
  std::set<uint> s;
  std::uniform_int_distribution<uint> d(0, 0xFFFFFFFEu);
  while (s.size() < n) s.insert(d(rng));
  std::vector<uint> v(s.begin(), s.end());
  std::shuffle(v.begin(), v.end(), rng);
  return v;
}

// Parity of the permutation taking a to b (both hold the same 4 values).
int parity(const uint* a, const uint* b) {
  int perm[4];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (b[i] == a[j]) perm[i] = j;
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inversions += perm[i] > perm[j];
  return inversions & 1;
}

struct Entry {
  uint k[4];
  uint n;
};

// All ways an entry face can be presented: each rotation of its outward cycle; for quads also each
// run of three consecutive vertices (how shell triangles of split quads present them).
std::vector<Entry> entries(CellType t, uint f, const uint* v) {
  std::vector<Entry> out;
  uint fs = faceSize(t, f);
  for (uint r = 0; r < fs; ++r) {
    Entry e{};
    e.n = fs;
    for (uint j = 0; j < fs; ++j) e.k[j] = v[faceVert(t, f, (r + j) % fs)];
    out.push_back(e);
    if (fs == 4) {
      Entry tri = e;
      tri.n = 3;
      tri.k[3] = 0;
      out.push_back(tri);
    }
  }
  return out;
}

TEST(XorCodec, RoundTripFromEveryEntryFace) {
  std::mt19937 rng(1234);
  int checked = 0;
  for (int trial = 0; trial < 200; ++trial) {
    for (CellType t : kAllCellTypes) {
      uint type = typeIndex(t);
      auto ids = randomIds(rng, numVerts(t));
      uint v[8] = {};
      std::copy(ids.begin(), ids.end(), v);
      uint rec[8], plain[8] = {};
      gpu::smXorEncode(type, v, rec);
      std::copy(v, v + 8, plain);
      for (uint f = 0; f < numFaces(t); ++f) {
        for (const Entry& e : entries(t, f, v)) {
          // Wedges need the whole quad: the shell supplies the fourth vertex for them.
          bool decodable = !(t == CellType::Wedge && faceSize(t, f) == 4 && e.n == 3);
          for (int mode = 0; mode < 2; ++mode) {
            uint out[8];
            int face = mode == 0 ? gpu::smXorDecode(type, rec, e.k, e.n, out)
                                 : gpu::smPlainDecode(type, plain, e.k, e.n, out);
            if (!decodable) continue;
            ++checked;
            if (t == CellType::Tet) {
              ASSERT_EQ(face, 3);
              EXPECT_EQ(parity(v, out), 0) << "tet decoded with flipped orientation";
              std::set<uint> want(v, v + 4), got(out, out + 4);
              EXPECT_EQ(want, got);
              // Face 3 of the decoded tet is the entry face.
              std::set<uint> entry(e.k, e.k + 3);
              std::set<uint> f3 = {out[0], out[1], out[2]};
              EXPECT_EQ(entry, f3);
            } else {
              ASSERT_EQ(face, int(f)) << cellTypeName(t) << " mode " << mode;
              for (uint i = 0; i < numVerts(t); ++i)
                EXPECT_EQ(out[i], v[i]) << cellTypeName(t) << " vertex " << i << " face " << f;
            }
          }
        }
      }
    }
  }
  EXPECT_GT(checked, 10000);
}

TEST(XorCodec, RejectsFacesThatDoNotBelong) {
  uint v[8] = {10, 20, 30, 40, 50, 60, 70, 80};
  uint rec[8];
  gpu::smXorEncode(gpu::SM_WED, v, rec);
  uint wrong[4] = {11, 12, 13, 14};
  uint out[8];
  EXPECT_EQ(gpu::smXorDecode(gpu::SM_WED, rec, wrong, 4, out), -1);
  EXPECT_EQ(gpu::smPlainDecode(gpu::SM_HEX, v, wrong, 4, out), -1);
  uint tri[4] = {10, 20, 99, 0};
  EXPECT_EQ(gpu::smPlainDecode(gpu::SM_TET, v, tri, 3, out), -1);
}

TEST(XorCodec, TetSlotIsRankOfOppositeVertex) {
  uint v[8] = {40, 10, 30, 20, 0, 0, 0, 0};
  EXPECT_EQ(gpu::smTetSlot(v, 10), 0u);
  EXPECT_EQ(gpu::smTetSlot(v, 20), 1u);
  EXPECT_EQ(gpu::smTetSlot(v, 30), 2u);
  EXPECT_EQ(gpu::smTetSlot(v, 40), 3u);
}

}  // namespace
}  // namespace sm::mesh
