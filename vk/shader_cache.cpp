#include "vk/shader_cache.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>

namespace sm::vk {
namespace {

constexpr char kMagic[8] = {'s', 'm', 'c', 'a', 'c', 'h', 'e', '\0'};

// Every file starts with this, little-endian as written by the host (a file from a host of the
// other byte order fails the format check).
struct FileHeader {
  char magic[8];
  uint32_t format;
  uint32_t kind;
  uint8_t uuid[16];
  uint32_t version, vendorId, deviceId, reserved;
  uint64_t key;
  uint64_t payloadBytes;
  uint64_t payloadHash;
};
static_assert(sizeof(FileHeader) == 72);
constexpr size_t kFormatBytes = offsetof(FileHeader, kind);

bool sameIdentity(const FileHeader& h, const CacheIdentity& id) {
  return std::memcmp(h.uuid, id.uuid, sizeof h.uuid) == 0 && h.version == id.version &&
         h.vendorId == id.vendorId && h.deviceId == id.deviceId;
}

void warn(const std::string& line) {
  std::fprintf(stderr, "shellmarch: warning: %s\n", line.c_str());
}

// Why `h` (of a file of `size` bytes) cannot be used; "" when it can.
std::string problem(const FileHeader& h, size_t size, ShaderCache::Kind kind,
                    const CacheIdentity& id, uint64_t key) {
  if (h.kind != kind) return "it holds another kind of cache data";
  if (!sameIdentity(h, id)) return "it was made by another device or driver";
  if (h.key != key) return "it was made for another shader";
  const uint64_t want = sizeof(FileHeader) + h.payloadBytes;
  if (size < want)
    return "it is truncated (" + std::to_string(size) + " of " + std::to_string(want) + " bytes)";
  if (size > want) return "it has " + std::to_string(size - want) + " bytes past its end";
  return "";
}

}  // namespace

uint64_t fnv1a(std::span<const uint8_t> bytes, uint64_t h) {
  for (uint8_t b : bytes) h = (h ^ b) * 0x100000001b3ull;
  return h;
}

ShaderCache::ShaderCache(std::string folder) : folder_(folder == "none" ? "" : std::move(folder)) {}

std::string ShaderCache::defaultFolder() {
  auto env = [](const char* name) {
    const char* v = std::getenv(name);
    return std::string(v ? v : "");
  };
  if (!env("SHELLMARCH_CACHE_DIR").empty()) return env("SHELLMARCH_CACHE_DIR");
  if (!env("XDG_CACHE_HOME").empty()) return env("XDG_CACHE_HOME") + "/shellmarch";
  if (!env("HOME").empty()) return env("HOME") + "/.cache/shellmarch";
  return "";
}

std::string ShaderCache::path(const std::string& name) const {
  return folder_ + "/" + name;
}

void ShaderCache::reject(const std::string& file, const std::string& why) const {
  ++rejected_;
  warn("ignoring cache file " + file + ": " + why + "; it is built again");
}

std::vector<uint8_t> ShaderCache::load(const std::string& name, Kind kind, const CacheIdentity& id,
                                       uint64_t key) const {
  if (!enabled()) return {};
  const std::string file = path(name);
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    ++misses_;
    return {};
  }
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
  FileHeader h{};
  std::memcpy(&h, bytes.data(), std::min(bytes.size(), sizeof h));
  std::string why;
  if (bytes.size() < kFormatBytes || std::memcmp(h.magic, kMagic, sizeof kMagic) != 0)
    why = bytes.size() < kFormatBytes
              ? "it is truncated (" + std::to_string(bytes.size()) + " bytes)"
              : "it is not a shellmarch cache file";
  else if (h.format > kFormat)
    why = "it was written by a newer shellmarch (cache format " + std::to_string(h.format) +
          "; this one reads format " + std::to_string(kFormat) + ")";
  else if (h.format < kFormat)
    why = "it has an older cache format (" + std::to_string(h.format) + ")";
  else if (bytes.size() < sizeof h)
    why = "it is truncated (" + std::to_string(bytes.size()) + " bytes)";
  else
    why = problem(h, bytes.size(), kind, id, key);
  std::span<const uint8_t> payload(bytes.data() + std::min(bytes.size(), sizeof h),
                                   bytes.size() - std::min(bytes.size(), sizeof h));
  if (why.empty() && fnv1a(payload) != h.payloadHash)
    why = "it is corrupt (its checksum does not match)";
  if (!why.empty()) {
    reject(file, why);
    return {};
  }
  ++hits_;
  return {payload.begin(), payload.end()};
}

bool ShaderCache::store(const std::string& name, Kind kind, const CacheIdentity& id, uint64_t key,
                        std::span<const uint8_t> payload) const {
  if (!enabled()) return false;
  FileHeader h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.format = kFormat;
  h.kind = kind;
  std::memcpy(h.uuid, id.uuid, sizeof h.uuid);
  h.version = id.version;
  h.vendorId = id.vendorId;
  h.deviceId = id.deviceId;
  h.key = key;
  h.payloadBytes = payload.size();
  h.payloadHash = fnv1a(payload);
  // A temporary name of this process and call, renamed over the file: readers in other
  // processes see the old file or the new one, whole.
  static std::atomic<uint64_t> serial{0};
  const std::string file = path(name);
  const std::string tmp =
      file + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(serial++);
  std::error_code ec;
  std::filesystem::create_directories(folder_, ec);
  bool ok = !ec;
  if (ok) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(&h), sizeof h);
    out.write(reinterpret_cast<const char*>(payload.data()), std::streamsize(payload.size()));
    out.close();
    ok = bool(out);
    if (!ok) ec = std::error_code(errno ? errno : EIO, std::generic_category());
  }
  if (ok) {
    std::filesystem::rename(tmp, file, ec);
    ok = !ec;
  }
  if (!ok) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    if (!unwritableWarned_.exchange(true))
      warn("cannot write the shader cache in " + folder_ + " (" + ec.message() +
           "): shaders will be compiled again by the next run (--cache-dir chooses another "
           "folder)");
    return false;
  }
  ++stored_;
  return true;
}

}  // namespace sm::vk
