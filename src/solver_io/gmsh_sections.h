// The sections of a Gmsh .msh 4.1 file (ASCII or binary), as gmsh_reader.cpp needs them: the
// nodes, the element blocks with the partition each belongs to, and where each $NodeData and
// $ElementData section's values lie (read only when a field is loaded).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "io_core/file_bytes.h"
#include "io_core/read_stop.h"

namespace sm::io {

// What Gmsh's element type number means here: its dimension, node count and corner count (the
// first `corners` nodes of every order are the linear element's, in the same order).
struct GmshElementType {
  int dim = -1;  // -1: a type this reader does not know (polygons, polyhedra, order 0, ...)
  uint32_t nodes = 0;
  uint32_t corners = 0;
  int vtkType = 0;  // the linear VTK cell of the corners (0 for 0D elements)
};
GmshElementType gmshElementType(int type);

struct GmshElementBlock {
  int dim = 0, entity = 0, type = 0;
  int piece = 0;  // partition - 1; 0 when the file is not partitioned
  uint64_t count = 0;
  // Full reads only: every element's tag, and the corners of volume elements (node tags).
  std::vector<uint64_t> tags;
  std::vector<uint64_t> corners;
  std::vector<const char*> lines;  // full ASCII reads: where each element starts, for messages
  const char* where = nullptr;     // the block's header, for messages
};

struct GmshDataSection {
  bool cells = false;  // $ElementData
  std::string name;
  double time = 0;
  int64_t step = 0;
  uint32_t components = 1;
  uint64_t count = 0;
  const char* values = nullptr;  // first entry (ASCII text or binary records)
};

struct GmshFile {
  bool binary = false;
  bool swap = false;
  int partitions = 0;              // $PartitionedEntities' count; 0: not partitioned
  std::vector<uint64_t> nodeTags;  // full reads only, in file order
  std::vector<glm::dvec3> nodes;
  std::vector<GmshElementBlock> blocks;
  std::vector<GmshDataSection> data;
};

class GmshParser {
 public:
  // `full`: read nodes and elements; otherwise only what the layout needs (block headers).
  GmshParser(const FileBytes& bytes, const std::string& source, bool full,
             const StopRequested& stop);
  GmshFile parse();

  // Calls visit(tag, values) for each entry of a data section (values: its components).
  void forEachValue(const GmshDataSection& s,
                    const std::function<void(int64_t, std::span<const double>)>& visit) const;

 private:
  class Cursor;
  void meshFormat(Cursor& c);
  void partitionedEntities(Cursor& c);
  void entity(Cursor& c, int dim);
  void nodesSection(Cursor& c);
  void nodeBlock(Cursor& c, uint64_t& declaredLeft);
  void elementsSection(Cursor& c);
  void elementBlock(Cursor& c, uint64_t& declaredLeft);
  void dataSection(Cursor& c, bool cells);
  void skipLines(Cursor& c, uint64_t n) const;
  void skipSection(Cursor& c, const std::string& name);
  void expectEnd(Cursor& c, const std::string& name);
  int pieceOf(int dim, int entity) const;

  const char* begin_;
  const char* end_;
  const std::string& src_;
  bool full_;
  StopRequested stop_;  // a copy: callers pass temporaries
  GmshFile file_;
  bool haveFormat_ = false, haveNodes_ = false, haveElements_ = false;
  // (dim, entity tag) -> partition of each partitioned entity, and ghost entities' tags.
  std::map<std::pair<int, int>, int> entityPartition_;
  std::vector<int> ghosts_;
};

}  // namespace sm::io
