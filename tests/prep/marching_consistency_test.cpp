// What the marcher relies on, checked on whole meshes: crossing any interior face from element A
// into element B, decoding B from A's exit face (in compact and plain mode) yields B's vertices,
// the right entry face, and a connectivity slot for that face that points back to A.
#include <gtest/gtest.h>

#include <set>

#include "prep/face_slots.h"
#include "prep/prepare.h"
#include "shared/xor_codec.h"
#include "support/test_meshes.h"

namespace sm::prep {
namespace {

void checkAllCrossings(mesh::UnstructuredMesh m) {
  auto copy = m;
  auto frame = makeGlobalFrame(m.bounds());
  PreparedRank compact = prepareRank(m, frame, PrepOptions{true}).rank;
  PreparedRank plain = prepareRank(copy, frame, PrepOptions{false}).rank;
  ASSERT_EQ(compact.positions, plain.positions);
  uint64_t crossings = 0;
  for (uint32_t ta = 0; ta < 4; ++ta) {
    const uint32_t nva = gpu::SM_NUM_VERTS[ta], nfa = gpu::SM_NUM_FACES[ta];
    for (uint64_t a = 0; a < plain.elementCount[ta]; ++a) {
      const uint32_t* va = &plain.elements[ta][a * nva];
      for (uint32_t s = 0; s < nfa; ++s) {
        uint32_t ref = plain.neighbors[ta][a * nfa + s];
        if (ref == gpu::SM_NO_NEIGHBOR) continue;
        ASSERT_EQ(ref, compact.neighbors[ta][a * nfa + s]);
        uint32_t exitFace[4];
        uint32_t n = FaceSlots::faceVertices(ta, va, s, exitFace);
        uint32_t k[4] = {0, 0, 0, 0};  // B's outward order: A's reversed
        for (uint32_t i = 0; i < n; ++i) k[i] = exitFace[n - 1 - i];
        uint32_t tb = gpu::smRefType(ref), b = gpu::smRefIndex(ref);
        const uint32_t nvb = gpu::SM_NUM_VERTS[tb];
        uint32_t vb[8] = {}, rec[8] = {}, out[8];
        for (uint32_t i = 0; i < nvb; ++i) vb[i] = plain.elements[tb][uint64_t(b) * nvb + i];
        const uint32_t cw = gpu::SM_COMPACT_WORDS[tb];
        for (uint32_t i = 0; i < cw; ++i) rec[i] = compact.elements[tb][uint64_t(b) * cw + i];
        for (int mode = 0; mode < 2; ++mode) {
          int face = mode == 0 ? gpu::smXorDecode(tb, rec, k, n, out)
                               : gpu::smPlainDecode(tb, vb, k, n, out);
          ASSERT_GE(face, 0);
          uint32_t slot;
          if (tb == gpu::SM_TET) {
            EXPECT_EQ(std::set<uint32_t>(out, out + 4), std::set<uint32_t>(vb, vb + 4));
            slot = gpu::smTetSlot(out, out[3]);  // entry face is opposite the fourth vertex
          } else {
            for (uint32_t i = 0; i < nvb; ++i) ASSERT_EQ(out[i], vb[i]);
            slot = uint32_t(face);
          }
          EXPECT_EQ(plain.neighbors[tb][uint64_t(b) * gpu::SM_NUM_FACES[tb] + slot],
                    gpu::smElemRef(uint32_t(a), ta));
          ++crossings;
        }
      }
    }
  }
  EXPECT_GT(crossings, 0u);
}

TEST(MarchingConsistency, Tetrahedra) {
  checkAllCrossings(test::kuhnTetGrid(3));
}
TEST(MarchingConsistency, Hexahedra) {
  checkAllCrossings(test::hexGrid(3));
}
TEST(MarchingConsistency, Wedges) {
  checkAllCrossings(test::wedgeGrid(3));
}
TEST(MarchingConsistency, Pyramids) {
  checkAllCrossings(test::pyramidGrid(3));
}

// Shell triangles give the marcher its first element: decoding from the triangle (with the quad's
// fourth vertex in compact mode) must yield that element.
TEST(MarchingConsistency, ShellEntries) {
  for (auto m :
       {test::kuhnTetGrid(2), test::hexGrid(2), test::wedgeGrid(2), test::pyramidGrid(2)}) {
    auto copy = m;
    auto frame = makeGlobalFrame(m.bounds());
    PreparedRank c = prepareRank(m, frame, PrepOptions{true}).rank;
    PreparedRank p = prepareRank(copy, frame, PrepOptions{false}).rank;
    for (uint64_t i = 0; i < c.numShellTriangles(); ++i) {
      uint32_t ref = c.shellRefs[i], t = gpu::smRefType(ref), e = gpu::smRefIndex(ref);
      uint32_t k[4] = {c.shellIndices[3 * i], c.shellIndices[3 * i + 1], c.shellIndices[3 * i + 2],
                       c.shellOther[i]};
      uint32_t n = k[3] == ~0u ? 3 : 4;
      uint32_t rec[8] = {}, vb[8] = {}, out[8];
      for (uint32_t w = 0; w < gpu::SM_COMPACT_WORDS[t]; ++w)
        rec[w] = c.elements[t][uint64_t(e) * gpu::SM_COMPACT_WORDS[t] + w];
      for (uint32_t w = 0; w < gpu::SM_NUM_VERTS[t]; ++w)
        vb[w] = p.elements[t][uint64_t(e) * gpu::SM_NUM_VERTS[t] + w];
      ASSERT_GE(gpu::smXorDecode(t, rec, k, n, out), 0);
      if (t == gpu::SM_TET) {
        EXPECT_EQ(std::set<uint32_t>(out, out + 4), std::set<uint32_t>(vb, vb + 4));
        EXPECT_EQ(p.neighbors[t][uint64_t(e) * 4 + gpu::smTetSlot(out, out[3])],
                  gpu::SM_NO_NEIGHBOR);
      } else {
        for (uint32_t w = 0; w < gpu::SM_NUM_VERTS[t]; ++w) EXPECT_EQ(out[w], vb[w]);
      }
      // Plain mode gets only the triangle (no fourth vertex): still enough.
      ASSERT_GE(gpu::smPlainDecode(t, vb, k, 3, out), 0);
    }
  }
}

}  // namespace
}  // namespace sm::prep
