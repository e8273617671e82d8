#include "compositor/tools/count_dump.h"

#include <bit>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "compositor/deep_compositor.h"

namespace sm::comp {
namespace {

constexpr char kMagic[8] = {'S', 'M', 'F', 'C', 'N', 'T', '0', '1'};
constexpr uint64_t kHeaderBytes = 8 + 4 * 4;
static_assert(std::endian::native == std::endian::little, "count dumps are little-endian");

std::runtime_error dumpError(const std::string& path, const std::string& what) {
  return std::runtime_error("fragment count dump " + path + ": " + what);
}

// Checked before the file is created: a constructor that throws has no destructor to remove it.
const std::string& checkedShape(const std::string& path, uint32_t width, uint32_t height,
                                uint32_t ranks) {
  if (width == 0 || height == 0 || ranks == 0) throw dumpError(path, "empty image or no ranks");
  return path;
}

}  // namespace

CountDumpWriter::CountDumpWriter(const std::string& path, uint32_t width, uint32_t height,
                                 uint32_t ranks)
    : path_(checkedShape(path, width, height, ranks)),
      temp_(path + ".part"),
      out_(temp_, std::ios::binary),
      pixels_(uint64_t(width) * height),
      ranks_(ranks) {
  if (!out_) throw dumpError(path, "cannot create " + temp_);
  const uint32_t header[4] = {width, height, ranks, 0};
  out_.write(kMagic, sizeof kMagic);
  out_.write(reinterpret_cast<const char*>(header), sizeof header);
}

void CountDumpWriter::append(std::span<const uint32_t> counts) {
  if (written_ == ranks_) throw dumpError(path_, "more ranks than the header says");
  if (counts.size() != pixels_)
    throw dumpError(path_, "rank " + std::to_string(written_) + " has " +
                               std::to_string(counts.size()) + " counts for " +
                               std::to_string(pixels_) + " pixels");
  out_.write(reinterpret_cast<const char*>(counts.data()), std::streamsize(counts.size_bytes()));
  if (!out_) throw dumpError(path_, "write failed");
  ++written_;
}

void CountDumpWriter::close() {
  if (written_ != ranks_)
    throw dumpError(path_,
                    std::to_string(written_) + " of " + std::to_string(ranks_) + " ranks written");
  out_.close();
  if (!out_) throw dumpError(path_, "write failed");
  if (std::rename(temp_.c_str(), path_.c_str()) != 0)
    throw dumpError(path_, "cannot rename " + temp_ + " to it");
  closed_ = true;
}

CountDumpWriter::~CountDumpWriter() {
  if (closed_) return;
  out_.close();
  std::remove(temp_.c_str());  // an unfinished dump must not be mistaken for a whole one
}

CountDumpReader::CountDumpReader(const std::string& path)
    : path_(path), in_(path, std::ios::binary) {
  if (!in_) throw dumpError(path, "cannot open the file");
  char magic[8];
  uint32_t header[4];
  in_.read(magic, sizeof magic);
  in_.read(reinterpret_cast<char*>(header), sizeof header);
  if (!in_ || std::memcmp(magic, kMagic, sizeof kMagic) != 0)
    throw dumpError(path, "not a fragment count dump (magic SMFCNT01 expected)");
  width_ = header[0];
  height_ = header[1];
  ranks_ = header[2];
  if (width_ == 0 || height_ == 0 || ranks_ == 0) throw dumpError(path, "empty image or no ranks");
  in_.seekg(0, std::ios::end);
  const uint64_t want = kHeaderBytes + uint64_t(width_) * height_ * ranks_ * 4;
  if (uint64_t(in_.tellg()) != want)
    throw dumpError(path, "size " + std::to_string(uint64_t(in_.tellg())) + " bytes, header says " +
                              std::to_string(want));
}

void CountDumpReader::read(uint32_t rank, std::vector<uint32_t>& counts) {
  if (rank >= ranks_)
    throw dumpError(path_, "rank " + std::to_string(rank) + " of " + std::to_string(ranks_));
  const uint64_t pixels = uint64_t(width_) * height_;
  counts.resize(pixels);
  in_.clear();
  in_.seekg(std::streamoff(kHeaderBytes + uint64_t(rank) * pixels * 4));
  in_.read(reinterpret_cast<char*>(counts.data()), std::streamsize(pixels * 4));
  if (!in_) throw dumpError(path_, "read of rank " + std::to_string(rank) + " failed");
}

uint32_t dumpFrameCounts(DeepCompositor& compositor, const std::string& path) {
  const std::vector<std::vector<uint32_t>> counts = compositor.gatherCounts();
  if (counts.empty()) return 0;  // not rank 0
  CountDumpWriter w(path, uint32_t(compositor.width()), uint32_t(compositor.height()),
                    uint32_t(counts.size()));
  for (const auto& c : counts) w.append(c);
  w.close();
  return uint32_t(counts.size());
}

}  // namespace sm::comp
