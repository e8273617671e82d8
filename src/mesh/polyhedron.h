// General polyhedra (VTK_POLYHEDRON, the cells of OpenFOAM, Fluent and STAR-CCM+ polyhedral
// meshes) as tetrahedra, without new points: every field and time step, streamed or not, keeps
// its one value per point of the file.
//
// The split has to be conforming, or the element walk would stop at every face between two
// polyhedra: two cells that share a face must cut it into the same triangles. So a face's
// triangles depend only on the face (its points and their positions), never on the cell asking
// (triangulateFace), and the cell is the union of the cones from one of its vertices, the apex,
// over those triangles. "First" orders points by position (x, then y, then z; ties by id), not
// by id, so that the pieces of a partitioned file, which number a shared point differently,
// agree. A triangle holding the apex has no cone, nor has one flat with it (a planar face on the
// apex); on a warped face on the apex, a triangle away from it is a thin cone of its own, so the
// cell ends on the face's own cut and its neighbour meets it there, with no gap or overlap. The
// apex is the first vertex that sees every cone from inside and leaves no flat triangle that is
// not a fan from it (the first vertex of a convex cell, which begins each of its faces); failing
// that, the first that sees every cone, the flat triangles dropped: a planar face on it then ends
// the cell on the apex's fan, which may differ from the neighbour's cut of the same plane. The
// renderer meets such a face as two touching shells, which its traversal handles (docs/DESIGN.md),
// at the cost of a segment per ray through it.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace sm::mesh {

// A polyhedron's faces: face f is ids[offsets[f] .. offsets[f + 1]), a cycle of point ids.
struct PolyhedronFaces {
  std::vector<uint32_t> ids;
  std::vector<uint32_t> offsets{0};
  size_t numFaces() const { return offsets.size() - 1; }
  std::span<const uint32_t> face(size_t f) const {
    return {ids.data() + offsets[f], offsets[f + 1] - offsets[f]};
  }
};

// Why a polyhedron was not split.
enum class PolyhedronSplit {
  Ok,
  NotClosed,      // some edge is not on exactly two faces, once each way (open or mis-oriented)
  NotStarShaped,  // no vertex sees all the faces it is not on from inside
  BadFace,        // a face with fewer than 3 points, a point twice, or no valid triangulation
  TooLarge,       // more faces, or points on a face, than any solver's cell has (kMaxPolyhedron*)
};
// Bounds on the work one cell can ask for (ear clipping is cubic in a face's points, the apex
// search the product of vertices and triangles): far above the cells of polyhedral meshes.
constexpr size_t kMaxPolyhedronFaces = 1024;
constexpr size_t kMaxFacePoints = 256;
constexpr size_t kMaxEarClipPoints = 64;  // larger faces must be fans from their first point
constexpr size_t kMaxApexTries = 32;
const char* describe(PolyhedronSplit s);

// The triangles of face `cycle`, in its orientation. The same triangles (as vertex sets) for either
// orientation of the same face: the face is read from its first point, towards the earlier
// neighbour. A fan from that point when every triangle of it is proper, else ear clipping in that
// order (faces with points on straight edges, non-convex faces). False if no proper triangulation
// was found (a degenerate face).
bool triangulateFace(std::span<const uint32_t> cycle, const std::vector<glm::dvec3>& points,
                     std::vector<std::array<uint32_t, 3>>& tris);

// The tetrahedra of polyhedron `faces`, in VTK vertex order with positive volume, appended to
// `tets` (left as it was unless Ok). Faces may be oriented all outward or all inward. At most
// kMaxApexTries vertices are tried as the apex (header comment).
PolyhedronSplit tetrahedralize(const PolyhedronFaces& faces, const std::vector<glm::dvec3>& points,
                               std::vector<std::array<uint32_t, 4>>& tets);

}  // namespace sm::mesh
