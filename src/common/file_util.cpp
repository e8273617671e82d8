#include "common/file_util.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "common/fault_injection.h"

namespace sm {
namespace fs = std::filesystem;

std::vector<uint8_t> readFile(const std::string& path) {
  // A folder or a device (/dev/zero) opens too, and reads without end.
  std::error_code ec;
  if (fs::exists(path, ec) && !fs::is_regular_file(path, ec))
    throw FileError(path, "not a regular file");
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw FileError(path, "cannot open: ", std::strerror(errno));
  std::vector<uint8_t> data;
  if (std::fseek(f, 0, SEEK_END) == 0) {
    long size = std::ftell(f);
    if (size > 0) data.reserve(static_cast<size_t>(size));
    std::fseek(f, 0, SEEK_SET);
  }
  uint8_t buf[1 << 16];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) data.insert(data.end(), buf, buf + n);
  bool failed = std::ferror(f);
  std::fclose(f);
  if (failed) throw FileError(path, "read error");
  return data;
}

std::string readTextFile(const std::string& path) {
  auto bytes = readFile(path);
  return std::string(bytes.begin(), bytes.end());
}

void writeFileAtomically(const std::string& path,
                         const std::function<void(const std::string&)>& write) {
  static std::atomic<unsigned> counter{0};
  std::string tmp = concat(path, ".tmp.", ::getpid(), ".", counter++);
  try {
    write(tmp);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    const std::string why = ec.message();
    fs::remove(tmp, ec);
    throw FileError(path, "cannot write: ", why);
  }
}

void writeBytesAtomically(const std::string& path, std::span<const uint8_t> bytes) {
  writeFileAtomically(path, [&](const std::string& tmp) {
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw FileError(path, "cannot create: ", std::strerror(errno));
    // Written in two halves so that fault injection can stop a process between them, with a
    // partial file on disk under the temporary name.
    const size_t half = bytes.size() / 2;
    size_t n = half ? std::fwrite(bytes.data(), 1, half, f) : 0;
    bool ok = n == half && std::fflush(f) == 0;
    try {
      fault::atWrite(path);
    } catch (...) {
      std::fclose(f);
      throw;
    }
    if (ok && bytes.size() > half) n += std::fwrite(bytes.data() + half, 1, bytes.size() - half, f);
    ok = ok && n == bytes.size() && std::fflush(f) == 0;
    ok = (std::fclose(f) == 0) && ok;
    if (!ok) throw FileError(path, "write failed (disk full?)");
  });
}

std::string fileExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string directoryOf(const std::string& path) {
  return fs::path(path).parent_path().string();
}

std::string joinPath(const std::string& dir, const std::string& file) {
  if (dir.empty() || fs::path(file).is_absolute()) return file;
  return (fs::path(dir) / file).string();
}

bool fileExists(const std::string& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

uint64_t fileSize(const std::string& path) {
  std::error_code ec;
  auto s = fs::file_size(path, ec);
  if (ec) throw FileError(path, "cannot stat: ", ec.message());
  return s;
}

}  // namespace sm
