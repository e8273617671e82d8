// Exodus II files through libexodusii, shared by the layout (headers) and the reader (bulk data).
// Every call's status is checked and turned into an sm::FileError naming the file and the place;
// the library is told never to print or exit (ex_opts(0)), and every file is closed on every
// path (ExodusFile owns the handle).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sm::io {

// An element block as its header says. Volume blocks are read; the rest (shells, bars, 2D and
// unknown types) are counted as skipped cells of `vtkType`'s kind.
struct ExodusBlock {
  int64_t id = 0;
  std::string name, type;
  int64_t elements = 0, nodesPerElement = 0;
  bool volume = false;
  int vtkType = 0;            // volume: VTK's Lagrange type of the shape (corners first, any order)
  int corners = 0;            // volume: corner nodes, the first of each element's node list
  std::string place() const;  // "block 3 'name'" for messages
};

struct ExodusHeader {
  int64_t nodes = 0, elements = 0;
  std::vector<ExodusBlock> blocks;
  std::vector<std::string> nodalVars, elemVars;
  std::vector<int> truth;  // blocks x elemVars: element variable v is stored on block b
  std::vector<double> times;
  uint64_t maxValues = 0;  // no array the file holds can have more values (from its size)
  uint64_t volumeCells() const;
};

class ExodusFile {
 public:
  explicit ExodusFile(std::string path);
  ~ExodusFile();
  ExodusFile(const ExodusFile&) = delete;
  ExodusFile& operator=(const ExodusFile&) = delete;

  int id() const { return id_; }
  const std::string& path() const { return path_; }
  const ExodusHeader& header() const { return header_; }
  // Throws sm::FileError naming the file, `what` and the library's message when rc < 0.
  void check(int rc, const std::string& what) const;
  // Throws unless `count` values of `what` fit in the file (a corrupt count must not allocate).
  void checkCount(uint64_t count, const std::string& what) const;

 private:
  void readHeader();
  void readBlocks();
  void readVariables();

  std::string path_;
  int id_ = -1;
  uint64_t fileSize_ = 0;
  ExodusHeader header_;
};

// The files of the mesh `path` names: `path` alone, or every file of a decomposed mesh
// (NAME.e.N.0 .. NAME.e.N.N-1) when path is one of them, or NAME.e and only the set exists.
std::vector<std::string> exodusFiles(const std::string& path);

// The end of the data a classic netCDF file's header describes (CDF-1, -2, -5); none for other
// files (netCDF-4 files are HDF5, whose library checks its end of file itself).
std::optional<uint64_t> netcdfClassicExtent(const std::string& path);

// A decomposed mesh's pieces are its files; one file's pieces are its element blocks.
inline bool exodusPiecesAreFiles(const std::string& path, const std::vector<std::string>& files) {
  return files.size() > 1 || files[0] != path;
}

}  // namespace sm::io
