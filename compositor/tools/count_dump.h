// Per-rank, per-pixel fragment counts of one frame in a file, so that the exchange can be replayed
// (replay.h) for rank counts this machine cannot run, from a real render or a synthetic model.
//
// Format (all integers little-endian):
//   8 bytes   magic "SMFCNT01"
//   4 x u32   width, height, ranks, 0 (reserved)
//   ranks x (width * height) u32   counts of rank 0, then rank 1, ...; pixel y * width + x, row 0
//                                  at the top (the compositor's pixel order)
// Written and read one rank at a time: a 552-rank 1024x1024 dump (2.3 GB) never sits in memory.
// The writer fills PATH.part and renames it on close(), so a dump that exists is complete.
#pragma once

#include <cstdint>
#include <fstream>
#include <span>
#include <string>
#include <vector>

namespace sm::comp {

class DeepCompositor;

class CountDumpWriter {
 public:
  CountDumpWriter(const std::string& path, uint32_t width, uint32_t height, uint32_t ranks);
  ~CountDumpWriter();  // without close(): removes the unfinished file
  CountDumpWriter(const CountDumpWriter&) = delete;
  CountDumpWriter& operator=(const CountDumpWriter&) = delete;
  // Appends the next rank's counts (width * height of them).
  void append(std::span<const uint32_t> counts);
  // Checks that every rank was written, flushes and renames the file into place.
  void close();

 private:
  std::string path_, temp_;
  std::ofstream out_;
  uint64_t pixels_;
  uint32_t ranks_, written_ = 0;
  bool closed_ = false;
};

class CountDumpReader {
 public:
  explicit CountDumpReader(const std::string& path);
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  uint32_t ranks() const { return ranks_; }
  // Reads rank `rank`'s counts (any order).
  void read(uint32_t rank, std::vector<uint32_t>& counts);

 private:
  std::string path_;
  std::ifstream in_;
  uint32_t width_ = 0, height_ = 0, ranks_ = 0;
};

// Collective: gathers every rank's counts of the compositor's last frame and writes them to `path`
// on rank 0. Returns the number of ranks written on rank 0, 0 on the others.
uint32_t dumpFrameCounts(DeepCompositor& compositor, const std::string& path);

}  // namespace sm::comp
