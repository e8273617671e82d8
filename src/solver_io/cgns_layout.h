// The CGNS reader's view of a file (cgns_layout.cpp): the open file, and the zones, sections and
// solutions its headers declare, shared by cgnsLayout and readCgns (cgns_reader.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "common/error.h"
#include "solver_io/pieced_readers.h"

namespace sm::io::cgns {

// An open file, closed on every path. libcgns keeps open files, its cg_goto position and its last
// error in globals, so one file is open at a time in the process (the lock).
class File {
 public:
  explicit File(const std::string& path);
  ~File();
  File(const File&) = delete;
  File& operator=(const File&) = delete;

  int fn() const { return fn_; }
  const std::string& path() const { return path_; }
  uint64_t bytes() const { return bytes_; }
  // Throws sm::FileError "PATH: WHERE: WHAT (libcgns's message)" unless rc is CG_OK.
  void check(int rc, const std::string& where, const std::string& what) const;
  // Throws unless `count` values of `size` bytes fit in the file: libcgns exits the process when an
  // allocation fails, so a damaged size must be caught before it reaches the library.
  void checkFits(uint64_t count, uint64_t size, const std::string& where,
                 const std::string& what) const;

 private:
  std::unique_lock<std::mutex> lock_;
  std::string path_;
  uint64_t bytes_ = 0;
  int fn_ = -1;
};

// A FlowSolution_t node: its index, name and its DataArrays' names.
struct Solution {
  int index = 0;
  std::string name;
  std::vector<std::string> fields;
};

struct Zone {
  int base = 0, zone = 0;
  std::string baseName, name;
  bool structured = false;
  std::array<int64_t, 3> dims{};  // structured: vertices along i, j, k
  uint64_t vertices = 0, cells = 0;
  // Solutions at Vertex and at CellCenter, in time order (FlowSolutionPointers, else file order).
  std::vector<Solution> vertexSolutions, cellSolutions;
  // "base 'B' zone 'Z'", for messages.
  std::string where() const;
};

struct Scan {
  std::vector<Zone> zones;  // the 3D zones: the pieces
  PiecedLayout layout;
  uint64_t skippedZones = 0, skippedCells = 0;  // in bases that are not 3D
};

Scan scan(const File& file);

}  // namespace sm::io::cgns
