#include "io_core/file_bytes.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <utility>

#include "common/error.h"

namespace sm::io {
namespace {

struct Fd {
  int fd;
  explicit Fd(int f) : fd(f) {}
  Fd(Fd&& o) noexcept : fd(std::exchange(o.fd, -1)) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  Fd& operator=(Fd&&) = delete;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

// Opens a regular file for reading. O_NONBLOCK: opening a FIFO would otherwise wait for a writer
// (forever); a regular file reads the same either way, and anything else is refused.
Fd openRegular(const std::string& path, struct stat& st) {
  Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
  if (f.fd < 0) throw FileError(path, "cannot open: ", std::strerror(errno));
  if (::fstat(f.fd, &st) != 0) throw FileError(path, "cannot stat: ", std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw FileError(path, "not a regular file");
  return f;
}

}  // namespace

std::string FileBytes::readPrefix(const std::string& path, size_t bytes) {
  struct stat st {};
  Fd f = openRegular(path, st);
  std::string head(std::min<size_t>(bytes, size_t(st.st_size)), '\0');
  size_t got = 0;
  while (got < head.size()) {
    const ssize_t n = ::read(f.fd, head.data() + got, head.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw FileError(path, "cannot read: ", std::strerror(errno));
    if (n == 0) break;
    got += size_t(n);
  }
  head.resize(got);
  return head;
}

FileBytes FileBytes::open(const std::string& path) {
  return map(path, true);
}

FileBytes FileBytes::openLazily(const std::string& path) {
  return map(path, false);
}

FileBytes FileBytes::map(const std::string& path, bool populate) {
  struct stat st {};
  Fd f = openRegular(path, st);
  FileBytes b;
  if (st.st_size == 0) return b;
  // Read-only, so that MAP_POPULATE maps the page cache as it is (a writable mapping would be
  // populated by copying every page). Populating up front is much cheaper than a fault per page
  // for a file read whole, and much dearer for one array of a file of many steps (mapping a
  // solver's 28 MB piece to read 150 KB of it took most of a step's read).
  void* p = ::mmap(nullptr, static_cast<size_t>(st.st_size), PROT_READ,
                   MAP_PRIVATE | (populate ? MAP_POPULATE : 0), f.fd, 0);
  if (p == MAP_FAILED) throw FileError(path, "cannot map into memory: ", std::strerror(errno));
  b.data_ = static_cast<uint8_t*>(p);
  b.size_ = static_cast<size_t>(st.st_size);
  b.mapped_ = true;
  return b;
}

FileBytes FileBytes::copyOf(std::span<const uint8_t> bytes) {
  FileBytes b;
  if (bytes.empty()) return b;
  b.owned_.reset(new uint8_t[bytes.size()]);
  std::memcpy(b.owned_.get(), bytes.data(), bytes.size());
  b.data_ = b.owned_.get();
  b.size_ = bytes.size();
  b.writable_ = true;
  return b;
}

uint8_t* FileBytes::writableData() {
  if (!writable_ && data_) {
    // Private mapping: writes go to copies of the pages written, never to the file.
    if (::mprotect(data_, size_, PROT_READ | PROT_WRITE) != 0)
      throw Error("cannot make a mapped file writable: ", std::strerror(errno));
    writable_ = true;
  }
  return data_;
}

FileBytes::FileBytes(FileBytes&& other) noexcept {
  *this = std::move(other);
}

FileBytes& FileBytes::operator=(FileBytes&& other) noexcept {
  if (this != &other) {
    release();
    data_ = std::exchange(other.data_, nullptr);
    size_ = std::exchange(other.size_, 0);
    mapped_ = std::exchange(other.mapped_, false);
    writable_ = std::exchange(other.writable_, false);
    owned_ = std::move(other.owned_);
  }
  return *this;
}

FileBytes::~FileBytes() {
  release();
}

void FileBytes::release() {
  if (mapped_ && data_) ::munmap(data_, size_);
  owned_.reset();
  data_ = nullptr;
  size_ = 0;
  mapped_ = false;
  writable_ = false;
}

}  // namespace sm::io
