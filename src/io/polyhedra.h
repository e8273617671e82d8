// Polyhedron cells (VTK type 42) as the files describe them: the face streams of legacy .vtk
// files and of .vtu files up to VTK 9.3 (`faces` and `faceoffsets`), and the face arrays of .vtu
// files from VTK 9.4 on (`face_connectivity`, `face_offsets`, `polyhedron_to_faces`,
// `polyhedron_offsets`). Both give mesh::PolyhedronFaces, which MeshBuilder splits.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <pugixml.hpp>

#include "io/vtu_document.h"
#include "mesh/polyhedron.h"

namespace sm::io {

// The stream [number of faces, n0, ids of face 0, n1, ids of face 1, ...] of cell `fileCell`;
// ids are checked against `numPoints` (the piece's) and shifted by `firstPoint`. Throws
// sm::FileError naming the cell when the stream is cut short, runs on, or names a point that is
// not there.
mesh::PolyhedronFaces facesFromStream(std::span<const int64_t> stream, const std::string& source,
                                      uint64_t fileCell, uint64_t numPoints,
                                      uint64_t firstPoint = 0);

// The polyhedra of one .vtu piece. Reads its face arrays when `types` has a polyhedron.
class VtuPolyhedra {
 public:
  VtuPolyhedra(const VtuDocument& doc, pugi::xml_node cells, std::span<const int64_t> types);
  // False when the piece has polyhedra but no faces for them (they are skipped).
  bool hasFaces() const { return layout_ != Layout::None; }
  // The faces of cell c of the piece (a polyhedron), its points numbered as in the whole file;
  // none when it lists more faces, or a face of more points, than a split takes
  // (mesh::kMaxPolyhedronFaces, kMaxFacePoints): face arrays can list one face many times, so a
  // small file could otherwise ask for a stream of any size.
  std::optional<mesh::PolyhedronFaces> faces(uint64_t c, uint64_t fileCell, uint64_t numPoints,
                                             uint64_t firstPoint) const;

 private:
  enum class Layout { None, Stream, FaceArrays };
  void readStream(const VtuDocument& doc, pugi::xml_node cells, std::span<const int64_t> types);
  void readFaceArrays(const VtuDocument& doc, pugi::xml_node cells, std::span<const int64_t> types);

  const std::string& src_;
  Layout layout_ = Layout::None;
  // Stream: cell c's stream is stream_[begin_[c], end_[c]). FaceArrays: cell c's faces are
  // cellFaces_[begin_[c], end_[c]), face f's ids faceIds_[faceBegin_[f], faceBegin_[f + 1]).
  std::vector<int64_t> stream_, cellFaces_, faceIds_;
  std::vector<uint64_t> begin_, end_, faceBegin_;
};

}  // namespace sm::io
