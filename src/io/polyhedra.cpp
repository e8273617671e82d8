#include "io/polyhedra.h"

#include <algorithm>

#include "common/error.h"
#include "io/vtu_arrays.h"

namespace sm::io {
namespace {

constexpr int64_t kPolyhedron = 42;

// End offsets (the .vtu convention) checked to grow from 0 and to stay below `limit` when given.
std::vector<uint64_t> endOffsets(const std::vector<int64_t>& v, const std::string& src,
                                 const char* name) {
  std::vector<uint64_t> out(v.size());
  int64_t prev = 0;
  for (size_t i = 0; i < v.size(); ++i) {
    if (v[i] < prev)
      throw FileError(src, name, ": entry ", i, " (", v[i], ") is ",
                      v[i] < 0 ? "negative" : "smaller than the one before");
    out[i] = uint64_t(prev = v[i]);
  }
  return out;
}

}  // namespace

mesh::PolyhedronFaces facesFromStream(std::span<const int64_t> stream, const std::string& source,
                                      uint64_t fileCell, uint64_t numPoints, uint64_t firstPoint) {
  auto fail = [&](auto&&... what) -> void {
    throw FileError(source, "cell ", fileCell, " (polyhedron): ", what...);
  };
  if (stream.empty()) fail("its face stream is empty");
  // PolyhedronFaces keeps 32-bit offsets into its ids.
  if (stream.size() > 0xFFFFFFFFull)
    fail("its face stream has ", stream.size(), " values, more than the ", 0xFFFFFFFFull,
         " one polyhedron may have");
  const int64_t numFaces = stream[0];
  if (numFaces < 1 || uint64_t(numFaces) > stream.size())
    fail("its face stream claims ", numFaces, " faces in ", stream.size(), " values");
  mesh::PolyhedronFaces out;
  out.offsets.reserve(size_t(numFaces) + 1);
  size_t pos = 1;
  for (int64_t f = 0; f < numFaces; ++f) {
    if (pos >= stream.size()) fail("its face stream ends before face ", f);
    const int64_t n = stream[pos++];
    if (n < 3) fail("face ", f, " has ", n, " points");
    if (uint64_t(n) > stream.size() - pos)
      fail("face ", f, " claims ", n, " points, past the end of its stream");
    for (int64_t k = 0; k < n; ++k) {
      const int64_t id = stream[pos + size_t(k)];
      if (id < 0 || uint64_t(id) >= numPoints)
        fail("refers to point ", id, " but ", firstPoint > 0 ? "its piece has " : "the file has ",
             numPoints, " points");
      out.ids.push_back(uint32_t(uint64_t(id) + firstPoint));
    }
    pos += size_t(n);
    out.offsets.push_back(uint32_t(out.ids.size()));
  }
  if (pos != stream.size())
    fail("its face stream has ", stream.size() - pos, " values after its last face");
  return out;
}

VtuPolyhedra::VtuPolyhedra(const VtuDocument& doc, pugi::xml_node cells,
                           std::span<const int64_t> types)
    : src_(doc.source()) {
  if (std::find(types.begin(), types.end(), kPolyhedron) == types.end()) return;
  if (findDataArray(cells, "faces") || findDataArray(cells, "faceoffsets"))
    readStream(doc, cells, types);
  else if (findDataArray(cells, "face_connectivity") || findDataArray(cells, "polyhedron_offsets"))
    readFaceArrays(doc, cells, types);
}

void VtuPolyhedra::readStream(const VtuDocument& doc, pugi::xml_node cells,
                              std::span<const int64_t> types) {
  pugi::xml_node faces = findDataArray(cells, "faces"), ends = findDataArray(cells, "faceoffsets");
  if (!faces || !ends)
    throw FileError(src_, "has polyhedra with a '", faces ? "faces" : "faceoffsets",
                    "' array but no '", faces ? "faceoffsets" : "faces", "' array");
  const std::vector<int64_t> offsets =
      toInt64(doc.decode(ends, types.size(), "faceoffsets", 1), src_, "faceoffsets");
  begin_.assign(types.size(), 0);
  end_.assign(types.size(), 0);
  int64_t prev = 0;
  for (size_t c = 0; c < types.size(); ++c) {
    if (types[c] != kPolyhedron) {
      // -1 there, as VTK writes it: an end given to another cell says the streams are not where
      // the polyhedra's entries put them (VTK would read a stream for that cell).
      if (offsets[c] >= 0)
        throw FileError(src_, "faceoffsets: cell ", c, " (VTK type ", types[c], ") has the entry ",
                        offsets[c], ", but only polyhedra (type 42) have faces: -1 expected");
      continue;
    }
    if (offsets[c] < prev)
      throw FileError(src_, "faceoffsets: polyhedron cell ", c, " ends at ", offsets[c],
                      ", before the previous one's end (", prev, ")");
    begin_[c] = uint64_t(prev);
    end_[c] = uint64_t(prev = offsets[c]);
  }
  stream_ = toInt64(doc.decode(faces, uint64_t(prev), "faces", 1), src_, "faces");
  layout_ = Layout::Stream;
}

void VtuPolyhedra::readFaceArrays(const VtuDocument& doc, pugi::xml_node cells,
                                  std::span<const int64_t> types) {
  const uint64_t numCells = types.size();
  auto need = [&](const char* name) {
    pugi::xml_node a = findDataArray(cells, name);
    if (!a) throw FileError(src_, "has polyhedra but no '", name, "' array");
    return a;
  };
  const std::vector<uint64_t> cellEnds =
      endOffsets(toInt64(doc.decode(need("polyhedron_offsets"), numCells, "polyhedron_offsets", 1),
                         src_, "polyhedron_offsets"),
                 src_, "polyhedron_offsets");
  const uint64_t numCellFaces = cellEnds.empty() ? 0 : cellEnds.back();
  cellFaces_ =
      toInt64(doc.decode(need("polyhedron_to_faces"), numCellFaces, "polyhedron_to_faces", 1), src_,
              "polyhedron_to_faces");
  int64_t lastFace = -1;
  for (size_t i = 0; i < cellFaces_.size(); ++i) {
    if (cellFaces_[i] < 0)
      throw FileError(src_, "polyhedron_to_faces: entry ", i, " is ", cellFaces_[i]);
    lastFace = std::max(lastFace, cellFaces_[i]);
  }
  // The faces are at least as many as the largest id says; VTK reads faces no polyhedron lists
  // (a writer's shared face list, one a filter left), and so do we.
  const std::vector<uint64_t> faceEnds =
      endOffsets(toInt64(doc.decode(need("face_offsets"), uint64_t(lastFace) + 1, "face_offsets", 1,
                                    Length::AtLeast),
                         src_, "face_offsets"),
                 src_, "face_offsets");
  faceIds_ = toInt64(doc.decode(need("face_connectivity"), faceEnds.empty() ? 0 : faceEnds.back(),
                                "face_connectivity", 1, Length::AtLeast),
                     src_, "face_connectivity");
  faceBegin_.assign(1, 0);
  faceBegin_.insert(faceBegin_.end(), faceEnds.begin(), faceEnds.end());
  begin_.resize(numCells);
  end_.resize(numCells);
  for (uint64_t c = 0; c < numCells; ++c) {
    begin_[c] = c == 0 ? 0 : cellEnds[c - 1];
    end_[c] = cellEnds[c];
    if (types[c] == kPolyhedron && end_[c] == begin_[c])
      throw FileError(src_, "polyhedron_offsets: polyhedron cell ", c, " has no faces (its entry ",
                      end_[c], " is the previous cell's)");
  }
  layout_ = Layout::FaceArrays;
}

std::optional<mesh::PolyhedronFaces> VtuPolyhedra::faces(uint64_t c, uint64_t fileCell,
                                                         uint64_t numPoints,
                                                         uint64_t firstPoint) const {
  if (layout_ == Layout::Stream)
    return facesFromStream(std::span(stream_).subspan(begin_[c], end_[c] - begin_[c]), src_,
                           fileCell, numPoints, firstPoint);
  if (end_[c] - begin_[c] > mesh::kMaxPolyhedronFaces) return std::nullopt;
  for (uint64_t i = begin_[c]; i < end_[c]; ++i) {
    const uint64_t f = uint64_t(cellFaces_[i]);
    if (faceBegin_[f + 1] - faceBegin_[f] > mesh::kMaxFacePoints) return std::nullopt;
  }
  // The same checks through the stream form: [faces, n0, ids..., ...].
  std::vector<int64_t> stream{int64_t(end_[c] - begin_[c])};
  for (uint64_t i = begin_[c]; i < end_[c]; ++i) {
    const uint64_t f = uint64_t(cellFaces_[i]);
    stream.push_back(int64_t(faceBegin_[f + 1] - faceBegin_[f]));
    stream.insert(stream.end(), faceIds_.begin() + std::ptrdiff_t(faceBegin_[f]),
                  faceIds_.begin() + std::ptrdiff_t(faceBegin_[f + 1]));
  }
  return facesFromStream(stream, src_, fileCell, numPoints, firstPoint);
}

}  // namespace sm::io
