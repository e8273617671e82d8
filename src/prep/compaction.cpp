#include "prep/compaction.h"

#include "shared/xor_codec.h"

namespace sm::prep {

std::vector<uint32_t> compactElements(uint32_t type, const std::vector<uint32_t>& plain) {
  const uint32_t nv = gpu::SM_NUM_VERTS[type], nw = gpu::SM_COMPACT_WORDS[type];
  const uint64_t count = plain.size() / nv;
  std::vector<uint32_t> out(count * nw);
  for (uint64_t e = 0; e < count; ++e) {
    uint32_t v[8] = {}, rec[8];
    for (uint32_t i = 0; i < nv; ++i) v[i] = plain[e * nv + i];
    gpu::smXorEncode(type, v, rec);
    for (uint32_t i = 0; i < nw; ++i) out[e * nw + i] = rec[i];
  }
  return out;
}

uint32_t plainBytes(uint32_t type) {
  return 4 * gpu::SM_PLAIN_WORDS[type];
}
uint32_t compactBytes(uint32_t type) {
  return 4 * gpu::SM_COMPACT_WORDS[type];
}

}  // namespace sm::prep
