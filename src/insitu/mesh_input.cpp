#include "mesh_input.h"

#include <array>
#include <cstdint>

#include "common/error.h"
#include "mesh/mesh_builder.h"

namespace sm::insitu {
namespace {

using shellmarch::insitu::IndexSpan;
using shellmarch::insitu::MeshView;

struct TypedIds {
  mesh::CellType type;
  const char* member;  // the MeshView member, for messages
  const IndexSpan& ids;
};

std::array<TypedIds, 4> typedIds(const MeshView& v) {
  return {{{mesh::CellType::Tet, "tetrahedra", v.tetrahedra},
           {mesh::CellType::Pyramid, "pyramids", v.pyramids},
           {mesh::CellType::Wedge, "wedges", v.wedges},
           {mesh::CellType::Hex, "hexahedra", v.hexahedra}}};
}

std::vector<glm::dvec3> copyPoints(std::span<const double> xyz) {
  if (xyz.size() % 3 != 0)
    throw Error("setMesh: points holds ", xyz.size(),
                " values, not a multiple of 3 (x, y, z per vertex)");
  std::vector<glm::dvec3> points(xyz.size() / 3);
  for (size_t i = 0; i < points.size(); ++i)
    points[i] = glm::dvec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  return points;
}

// Sizes and id ranges of one type, before any cell is built: MeshBuilder's own messages speak of
// files, these speak of the arrays the caller passed.
void checkIds(const TypedIds& t, uint64_t numPoints) {
  const uint32_t nv = mesh::numVerts(t.type);
  if (t.ids.size() % nv != 0)
    throw Error("setMesh: ", t.member, " holds ", t.ids.size(), " ids, not a multiple of ", nv,
                " (ids per ", mesh::cellTypeName(t.type), ")");
  for (size_t i = 0; i < t.ids.size(); ++i) {
    const int64_t id = t.ids[i];
    if (id < 0 || uint64_t(id) >= numPoints)
      throw Error("setMesh: ", mesh::cellTypeName(t.type), " ", i / nv, " (", t.member, "[", i,
                  "]) refers to vertex ", id, ", but points gives ", numPoints,
                  " vertices (ids are 0-based)");
  }
}

// The polyhedra's face streams, one after another, checked with messages that name the array
// position; returns how many there were.
uint64_t addPolyhedra(const IndexSpan& s, uint64_t firstElement, mesh::MeshBuilder& builder) {
  mesh::PolyhedronFaces faces;
  uint64_t count = 0;
  for (size_t pos = 0; pos < s.size(); ++count) {
    const size_t start = pos;
    auto fail = [&](auto&&... what) {
      throw Error("setMesh: polyhedron ", count, " (polyhedra[", start, "]) ", what...);
    };
    // Fewer than 4 faces cannot close: the builder skips such a cell with a warning, as readers
    // do; only a stream that cannot be followed is an error.
    const int64_t numFaces = s[pos++];
    if (numFaces < 1 || uint64_t(numFaces) > s.size() - pos)
      fail("claims ", numFaces, " faces (at least 1, each 4 values or more, before the end)");
    faces.ids.clear();
    faces.offsets.assign(1, 0);
    for (int64_t f = 0; f < numFaces; ++f) {
      if (pos >= s.size()) fail("ends before its face ", f);
      const int64_t n = s[pos++];
      if (n < 3 || uint64_t(n) > s.size() - pos)
        fail("face ", f, " claims ", n, " vertices", n < 3 ? " (at least 3)" : ", past the end");
      for (int64_t k = 0; k < n; ++k, ++pos) {
        const int64_t id = s[pos];
        if (id < 0 || uint64_t(id) >= builder.numPoints())
          fail("refers to vertex ", id, " (polyhedra[", pos, "]), but points gives ",
               builder.numPoints(), " vertices (ids are 0-based)");
        faces.ids.push_back(uint32_t(id));
      }
      faces.offsets.push_back(uint32_t(faces.ids.size()));
    }
    builder.addPolyhedron(faces, firstElement + count);
  }
  return count;
}

}  // namespace

mesh::UnstructuredMesh meshFromView(const MeshView& view) {
  // The builder's messages start with its source name; here that is the API call.
  mesh::MeshBuilder builder("setMesh");
  builder.setPoints(copyPoints(view.points));
  uint64_t element = 0;  // the caller's numbering: the four types in order, then the polyhedra
  for (const TypedIds& t : typedIds(view)) {
    checkIds(t, builder.numPoints());
    const uint32_t nv = mesh::numVerts(t.type);
    const uint64_t count = t.ids.size() / nv;
    builder.reserveCells(t.type, count);
    int64_t ids[8];
    for (uint64_t e = 0; e < count; ++e) {
      for (uint32_t k = 0; k < nv; ++k) ids[k] = t.ids[e * nv + k];
      builder.addCell(t.type, std::span<const int64_t>(ids, nv), element++);
    }
  }
  if (view.polyhedra.empty()) return builder.finish();
  element += addPolyhedra(view.polyhedra, element, builder);
  builder.keepCellOrigins(element);
  return builder.finish();
}

std::vector<uint64_t> globalIdsFromView(const MeshView& view) {
  const uint64_t vertices = view.points.size() / 3;
  if (view.globalIds.empty()) return {};
  if (view.globalIds.size() != vertices)
    throw Error("setMesh: globalIds holds ", view.globalIds.size(), " ids for ", vertices,
                " vertices (one per vertex, or none)");
  std::vector<uint64_t> ids(vertices);
  for (size_t i = 0; i < ids.size(); ++i) {
    const int64_t id = view.globalIds[i];
    if (id < 0) throw Error("setMesh: globalIds[", i, "] is ", id, "; global ids are not negative");
    ids[i] = uint64_t(id);
  }
  return ids;
}

}  // namespace sm::insitu
