// The bytes a classic netCDF file's header says its data fills (CDF-1, CDF-2 and CDF-5 headers).
// netCDF reads past the end of a truncated classic file as zeros, so an Exodus file cut short
// would otherwise load with zero coordinates and node numbers; the header gives every variable's
// offset, so the file's expected end is known before any data is read.
#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/error.h"
#include "io_core/file_bytes.h"
#include "solver_io/exodus_file.h"

namespace sm::io {
namespace {

class HeaderCursor {
 public:
  HeaderCursor(const FileBytes& bytes, const std::string& path, int version)
      : bytes_(bytes), path_(path), wide_(version == 5), offset64_(version != 1) {}

  uint64_t uint(size_t width) {
    if (width > bytes_.size() || pos_ > bytes_.size() - width)
      throw FileError(path_, "its netCDF header runs past the end of the file");
    uint64_t v = 0;
    for (size_t i = 0; i < width; ++i) v = (v << 8) | bytes_.data()[pos_ + i];
    pos_ += width;
    return v;
  }
  uint64_t count() { return uint(wide_ ? 8 : 4); }  // NON_NEG: nelems, lengths, dim ids
  uint64_t offset() { return uint(offset64_ ? 8 : 4); }
  uint64_t vsize() { return uint(wide_ ? 8 : 4); }
  void skip(uint64_t n) {
    if (n > bytes_.size() - pos_)
      throw FileError(path_, "its netCDF header runs past the end of the file");
    pos_ += n;
  }
  void skipPadded(uint64_t n) { skip(n > UINT64_MAX - 3 ? n : (n + 3) / 4 * 4); }
  void skipName() { skipPadded(count()); }
  // The list tag (or ABSENT's zero) and its element count.
  uint64_t list(uint32_t tag, const char* what) {
    const uint64_t t = uint(4), n = count();
    if (t != tag && !(t == 0 && n == 0))
      throw FileError(path_, "its netCDF header is damaged (", what, " list)");
    if (n > bytes_.size()) throw FileError(path_, "its netCDF header declares ", n, " ", what);
    return n;
  }
  void skipAttributes() {
    for (uint64_t n = list(0x0C, "attributes"); n > 0; --n) {
      skipName();
      const uint64_t size = typeSize(uint(4)), values = count();
      if (values > bytes_.size()) throw FileError(path_, "its netCDF header is damaged");
      skipPadded(values * size);
    }
  }
  uint64_t typeSize(uint64_t type) const {
    static const uint64_t sizes[] = {0, 1, 1, 2, 4, 4, 8, 1, 2, 4, 8, 8};
    if (type < 1 || type > 11 || (type > 6 && !wide_))
      throw FileError(path_, "its netCDF header names data type ", type);
    return sizes[type];
  }

 private:
  const FileBytes& bytes_;
  const std::string& path_;
  bool wide_, offset64_;
  uint64_t pos_ = 4;
};

uint64_t times(uint64_t a, uint64_t b, const std::string& path) {
  if (b != 0 && a > UINT64_MAX / b)
    throw FileError(path, "its netCDF header declares absurd sizes");
  return a * b;
}

}  // namespace

std::optional<uint64_t> netcdfClassicExtent(const std::string& path) {
  const FileBytes bytes = FileBytes::openLazily(path);
  const uint8_t* d = bytes.data();
  if (bytes.size() < 8 || d[0] != 'C' || d[1] != 'D' || d[2] != 'F' ||
      (d[3] != 1 && d[3] != 2 && d[3] != 5))
    return std::nullopt;  // netCDF-4 (HDF5): the HDF5 library checks its own end of file
  HeaderCursor c(bytes, path, d[3]);
  const uint64_t numrecs = c.count();
  const bool streaming = d[3] != 5 && numrecs == 0xFFFFFFFFu;  // records up to the end of file
  std::vector<uint64_t> dims;
  for (uint64_t n = c.list(0x0A, "dimensions"); n > 0; --n) {
    c.skipName();
    dims.push_back(c.count());
  }
  c.skipAttributes();
  struct Var {
    uint64_t begin, bytes;  // bytes: of one record for a record variable
    bool record;
  };
  std::vector<Var> vars;
  for (uint64_t n = c.list(0x0B, "variables"); n > 0; --n) {
    c.skipName();
    Var v{0, 1, false};
    const uint64_t rank = c.count();
    for (uint64_t k = 0; k < rank; ++k) {
      const uint64_t dim = c.count();
      if (dim >= dims.size()) throw FileError(path, "its netCDF header names dimension ", dim);
      if (k == 0 && dims[dim] == 0)
        v.record = true;
      else
        v.bytes = times(v.bytes, dims[dim], path);
    }
    c.skipAttributes();
    v.bytes = times(v.bytes, c.typeSize(c.uint(4)), path);
    c.vsize();
    v.begin = c.offset();
    vars.push_back(v);
  }
  // Records hold every record variable in turn, each padded to 4 bytes unless it is the only one.
  uint64_t recordSize = 0, records = 0;
  for (const Var& v : vars) records += v.record;
  for (const Var& v : vars)
    if (v.record) recordSize += records == 1 ? v.bytes : (v.bytes + 3) / 4 * 4;
  uint64_t end = 0;
  for (const Var& v : vars) {
    if (v.record && streaming) continue;
    const uint64_t extent =
        v.record ? (numrecs == 0 ? 0 : times(numrecs - 1, recordSize, path) + v.bytes) : v.bytes;
    if (extent > UINT64_MAX - v.begin)
      throw FileError(path, "its netCDF header declares absurd sizes");
    if (extent > 0) end = std::max(end, v.begin + extent);
  }
  return end;
}

}  // namespace sm::io
