// Compiled shaders kept between processes (docs/ARCHITECTURE.md, "Startup"): shader object
// binaries and the driver's pipeline cache, one file each in a cache folder
// ($SHELLMARCH_CACHE_DIR, else $XDG_CACHE_HOME/shellmarch, else ~/.cache/shellmarch; --cache-dir
// on the command line).
//
// Files are never trusted: each carries a header with the format, the device and driver it was
// made by, the shader key and a checksum of its payload. A file that is truncated, corrupt, from
// another device or driver, or written by a newer shellmarch is ignored with a one-line warning
// and rebuilt. Many ranks and processes may share a folder: a file is written under a temporary
// name and renamed over the old one, so that readers see a whole file, old or new. A folder that
// cannot be written costs speed, not the image: one warning, then the process goes on without
// storing.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <span>
#include <string>
#include <vector>

namespace sm::vk {

// What a file's payload is valid for: a driver's cache or binary UUID, its version, and the device.
struct CacheIdentity {
  uint8_t uuid[16] = {};
  uint32_t version = 0, vendorId = 0, deviceId = 0;
};

// 64-bit FNV-1a of `bytes`, continuing from `seed`.
uint64_t fnv1a(std::span<const uint8_t> bytes, uint64_t seed = 0xcbf29ce484222325ull);

class ShaderCache {
 public:
  // The header's layout; a file with a larger number was written by a newer shellmarch.
  static constexpr uint32_t kFormat = 1;
  enum Kind : uint32_t { kPipelineCache = 1, kShaderBinary = 2 };

  // No folder: nothing is read or stored.
  ShaderCache() = default;
  explicit ShaderCache(std::string folder);
  ShaderCache(const ShaderCache&) = delete;
  ShaderCache& operator=(const ShaderCache&) = delete;

  // $SHELLMARCH_CACHE_DIR, else $XDG_CACHE_HOME/shellmarch, else $HOME/.cache/shellmarch; ""
  // when none of them is set. The value "none" (option or variable) turns the cache off.
  static std::string defaultFolder();

  bool enabled() const { return !folder_.empty(); }
  const std::string& folder() const { return folder_; }

  // The payload of file `name` made for `id` and `key`; empty when there is none or it is
  // unusable (then with a warning naming the file and why).
  std::vector<uint8_t> load(const std::string& name, Kind kind, const CacheIdentity& id,
                            uint64_t key) const;
  // Writes file `name` atomically; false when it could not be written (a warning the first
  // time).
  bool store(const std::string& name, Kind kind, const CacheIdentity& id, uint64_t key,
             std::span<const uint8_t> payload) const;

  // What loads found and stores wrote, for the startup statistics.
  uint64_t hits() const { return hits_; }
  uint64_t misses() const { return misses_; }
  uint64_t rejected() const { return rejected_; }
  uint64_t stored() const { return stored_; }

 private:
  std::string path(const std::string& name) const;
  void reject(const std::string& file, const std::string& why) const;

  std::string folder_;
  mutable std::atomic<uint64_t> hits_{0}, misses_{0}, rejected_{0}, stored_{0};
  mutable std::atomic<bool> unwritableWarned_{false};
};

}  // namespace sm::vk
