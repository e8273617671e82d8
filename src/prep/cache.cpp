#include "prep/cache.h"

#include <cstring>

#include "common/error.h"
#include "common/file_util.h"
#include "common/hash.h"
#include "prep/compaction.h"
#include "prep/prepare.h"

namespace sm::prep {
namespace {

constexpr char kMagic[8] = {'S', 'M', 'P', 'R', 'E', 'P', '0', '1'};

struct Header {
  char magic[8];
  uint32_t version;
  uint32_t flags;  // bit 0: compact
  uint64_t key;
  uint64_t payloadBytes;
  uint64_t payloadHash;
  uint32_t sectionCount;
  uint32_t reserved[5];
};
static_assert(sizeof(Header) == 64);

struct SectionHeader {
  uint32_t id;
  uint32_t elementSize;
  uint64_t count;
};
static_assert(sizeof(SectionHeader) == 16);

// Section ids; per-type arrays use base + type.
enum : uint32_t {
  kFrame = 1,
  kPositions,
  kVertexSource,
  kShellIndices,
  kShellRefs,
  kShellOther,
  kCounts,
  kShellAdjacency,
  kElements = 16,
  kNeighbors = 32
};

class Writer {
 public:
  template <typename T>
  void section(uint32_t id, const T* data, uint64_t count) {
    SectionHeader h{id, uint32_t(sizeof(T)), count};
    append(&h, sizeof h);
    append(data, count * sizeof(T));
    while (bytes_.size() % 8) bytes_.push_back(0);
    ++sections_;
  }
  template <typename T>
  void section(uint32_t id, const std::vector<T>& v) {
    section(id, v.data(), v.size());
  }
  std::vector<uint8_t>& bytes() { return bytes_; }
  uint32_t sections() const { return sections_; }

 private:
  void append(const void* p, size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    bytes_.insert(bytes_.end(), b, b + n);
  }
  std::vector<uint8_t> bytes_;
  uint32_t sections_ = 0;
};

struct Corrupt {
  std::string reason;
};

class Reader {
 public:
  Reader(const uint8_t* p, size_t n) : p_(p), n_(n) {}
  template <typename T>
  std::vector<T> section(uint32_t id) {
    if (n_ - pos_ < sizeof(SectionHeader)) throw Corrupt{"truncated section header"};
    SectionHeader h;
    std::memcpy(&h, p_ + pos_, sizeof h);
    pos_ += sizeof h;
    if (h.id != id) throw Corrupt{concat("section ", h.id, " where ", id, " was expected")};
    if (h.elementSize != sizeof(T))
      throw Corrupt{concat("section ", id, " has element size ", h.elementSize)};
    if (h.count > (n_ - pos_) / sizeof(T))
      throw Corrupt{concat("section ", id, " runs past the end")};
    std::vector<T> v(h.count);
    if (h.count) std::memcpy(v.data(), p_ + pos_, h.count * sizeof(T));
    pos_ += h.count * sizeof(T);
    pos_ = std::min(n_, (pos_ + 7) & ~size_t(7));
    return v;
  }
  bool atEnd() const { return pos_ == n_; }

 private:
  const uint8_t* p_;
  size_t n_, pos_ = 0;
};

// Sizes within the shaders' 32-bit word indices, as preparation checked them when it wrote the
// cache.
void validateSizes(const PreparedRank& r) {
  SceneSizes sizes;
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t) sizes.elements[t] = r.elementCount[t];
  sizes.vertices = r.vertexSource.size();
  sizes.shellTriangles = r.shellRefs.size();
  try {
    checkShaderIndexRange("cache", sizes, r.compact);
  } catch (const Error& e) {
    throw Corrupt{e.what()};
  }
}

// Every index must be in range so that a corrupt cache can never make a shader read out of bounds.
void validate(const PreparedRank& r) {
  const uint64_t nv = r.vertexSource.size();
  if (r.positions.size() != 3 * nv) throw Corrupt{"position count does not match vertex count"};
  validateSizes(r);
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t) {
    const uint64_t n = r.elementCount[t];
    if (n >= gpu::SM_MAX_ELEMS_PER_TYPE) throw Corrupt{"element count out of range"};
    const uint32_t words = (r.compact ? compactBytes(t) : plainBytes(t)) / 4;
    if (r.elements[t].size() != n * words)
      throw Corrupt{concat("element array ", t, " has the wrong size")};
    if (r.neighbors[t].size() != n * gpu::SM_NUM_FACES[t])
      throw Corrupt{concat("neighbour array ", t, " has the wrong size")};
    bool plainIds = !r.compact || t == gpu::SM_HEX;
    if (plainIds)
      for (uint32_t v : r.elements[t])
        if (v >= nv) throw Corrupt{"element vertex id out of range"};
    for (uint32_t ref : r.neighbors[t])
      if (ref != gpu::SM_NO_NEIGHBOR && gpu::smRefIndex(ref) >= r.elementCount[gpu::smRefType(ref)])
        throw Corrupt{"neighbour reference out of range"};
  }
  const uint64_t nt = r.shellRefs.size();
  if (r.shellIndices.size() != 3 * nt) throw Corrupt{"shell index count does not match"};
  if (r.compact ? r.shellOther.size() != nt : !r.shellOther.empty())
    throw Corrupt{"shell quad vertices do not match"};
  for (uint32_t v : r.shellIndices)
    if (v >= nv) throw Corrupt{"shell vertex id out of range"};
  for (uint32_t v : r.shellOther)
    if (v != ~0u && v >= nv) throw Corrupt{"shell quad vertex out of range"};
  if (r.shellAdjacency.size() != 3 * nt) throw Corrupt{"shell adjacency count does not match"};
  for (uint32_t a : r.shellAdjacency)
    if (a != ~0u && a >= nt) throw Corrupt{"shell adjacency out of range"};
  for (uint32_t ref : r.shellRefs)
    if (gpu::smRefIndex(ref) >= r.elementCount[gpu::smRefType(ref)])
      throw Corrupt{"shell element reference out of range"};
}

}  // namespace

uint64_t cacheKey(const mesh::UnstructuredMesh& m, const GlobalFrame& frame,
                  const PrepOptions& options, const std::string& layout) {
  Hasher h;
  h.pod(kCacheFormatVersion).str(layout).pod(options.compact);
  h.pod(frame.origin).pod(frame.bounds.lo).pod(frame.bounds.hi).pod(frame.scale);
  h.span(std::span<const glm::dvec3>(m.points));
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t) {
    h.span(std::span<const uint32_t>(m.cells[t]));
    h.span(std::span<const int32_t>(m.clusters[t]));
  }
  return h.digest();
}

void writeCache(const std::string& path, const PreparedRank& r, uint64_t key) {
  Writer w;
  double frame[10] = {r.frame.origin.x,    r.frame.origin.y,    r.frame.origin.z,
                      r.frame.bounds.lo.x, r.frame.bounds.lo.y, r.frame.bounds.lo.z,
                      r.frame.bounds.hi.x, r.frame.bounds.hi.y, r.frame.bounds.hi.z,
                      r.frame.scale};
  w.section(kFrame, frame, 10);
  w.section(kCounts, r.elementCount.data(), r.elementCount.size());
  w.section(kPositions, r.positions);
  w.section(kVertexSource, r.vertexSource);
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t) {
    w.section(kElements + t, r.elements[t]);
    w.section(kNeighbors + t, r.neighbors[t]);
  }
  w.section(kShellIndices, r.shellIndices);
  w.section(kShellRefs, r.shellRefs);
  w.section(kShellOther, r.shellOther);
  w.section(kShellAdjacency, r.shellAdjacency);
  Header h{};
  std::memcpy(h.magic, kMagic, 8);
  h.version = kCacheFormatVersion;
  h.flags = r.compact ? 1 : 0;
  h.key = key;
  h.payloadBytes = w.bytes().size();
  h.payloadHash = hashBytes(w.bytes().data(), w.bytes().size());
  h.sectionCount = w.sections();
  std::vector<uint8_t> file(sizeof h);
  std::memcpy(file.data(), &h, sizeof h);
  file.insert(file.end(), w.bytes().begin(), w.bytes().end());
  writeBytesAtomically(path, file);
}

CacheRead parseCache(const uint8_t* data, size_t size, uint64_t key) {
  CacheRead out;
  auto corrupt = [&](std::string why) {
    out.status = CacheStatus::Corrupt;
    out.reason = std::move(why);
    out.rank.reset();
    return out;
  };
  if (size < sizeof(Header)) return corrupt("shorter than its header");
  Header h;
  std::memcpy(&h, data, sizeof h);
  if (std::memcmp(h.magic, kMagic, 8) != 0) return corrupt("not a shellmarch preparation cache");
  if (h.version != kCacheFormatVersion) {
    out.status = CacheStatus::Stale;
    out.reason = concat("format version ", h.version, ", this build writes ", kCacheFormatVersion);
    return out;
  }
  if (h.key != key) {
    out.status = CacheStatus::Stale;
    out.reason = "made from different input or rank layout";
    return out;
  }
  if (h.payloadBytes != size - sizeof h)
    return corrupt("payload size does not match the file size");
  if (hashBytes(data + sizeof h, h.payloadBytes) != h.payloadHash)
    return corrupt("checksum mismatch");
  try {
    Reader rd(data + sizeof h, h.payloadBytes);
    PreparedRank r;
    r.compact = h.flags & 1;
    auto frame = rd.section<double>(kFrame);
    if (frame.size() != 10 || !(frame[9] > 0)) throw Corrupt{"bad frame section"};
    r.frame.origin = {frame[0], frame[1], frame[2]};
    r.frame.bounds.lo = {frame[3], frame[4], frame[5]};
    r.frame.bounds.hi = {frame[6], frame[7], frame[8]};
    r.frame.bounds.empty = false;
    r.frame.scale = frame[9];
    auto counts = rd.section<uint64_t>(kCounts);
    if (counts.size() != mesh::kNumCellTypes) throw Corrupt{"bad element count section"};
    std::copy(counts.begin(), counts.end(), r.elementCount.begin());
    r.positions = rd.section<float>(kPositions);
    r.vertexSource = rd.section<uint32_t>(kVertexSource);
    for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t) {
      r.elements[t] = rd.section<uint32_t>(kElements + t);
      r.neighbors[t] = rd.section<uint32_t>(kNeighbors + t);
    }
    r.shellIndices = rd.section<uint32_t>(kShellIndices);
    r.shellRefs = rd.section<uint32_t>(kShellRefs);
    r.shellOther = rd.section<uint32_t>(kShellOther);
    r.shellAdjacency = rd.section<uint32_t>(kShellAdjacency);
    if (!rd.atEnd()) throw Corrupt{"trailing bytes"};
    validate(r);
    out.status = CacheStatus::Hit;
    out.rank = std::move(r);
  } catch (const Corrupt& c) {
    return corrupt(c.reason);
  }
  return out;
}

CacheRead readCache(const std::string& path, uint64_t key) {
  if (!fileExists(path)) return {};
  std::vector<uint8_t> bytes;
  try {
    bytes = readFile(path);
  } catch (const Error& e) {
    return {CacheStatus::Corrupt, e.what(), std::nullopt};
  }
  return parseCache(bytes.data(), bytes.size(), key);
}

}  // namespace sm::prep
