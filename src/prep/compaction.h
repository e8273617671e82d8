// XOR compaction of element records (the paper's "XOR-compaction").
#pragma once

#include <cstdint>
#include <vector>

namespace sm::prep {

// Compacted records of `count` elements of `type` given plain VTK-ordered ids (shared codec).
std::vector<uint32_t> compactElements(uint32_t type, const std::vector<uint32_t>& plain);

// Bytes per element, plain and compacted: tet 16/4, pyramid 20/16, wedge 24/16, hexahedron 32/32.
uint32_t plainBytes(uint32_t type);
uint32_t compactBytes(uint32_t type);

}  // namespace sm::prep
