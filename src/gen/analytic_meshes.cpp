// Tiny analytic meshes for tests. Elements are listed in VTK vertex order and mirrored here when
// a construction yields the other handedness (a cube's tetrahedra come in both), so MeshBuilder
// finds nothing to fix and prints nothing.
#include <array>
#include <functional>

#include "common/check.h"
#include "common/error.h"
#include "gen/generate.h"
#include "gen/volume_assembly.h"
#include "mesh/element_geometry.h"

namespace sm::gen {
namespace {

using mesh::CellType;

// A VolumeAssembly whose cells are mirrored into positive orientation as they are added.
struct CellList : VolumeAssembly {
  void add(CellType type, std::initializer_list<uint32_t> ids) {
    SM_CHECK_EQ(ids.size(), mesh::numVerts(type));
    std::array<uint32_t, 8> v{};
    std::copy(ids.begin(), ids.end(), v.begin());
    std::span<uint32_t> span(v.data(), ids.size());
    if (mesh::signedVolume(type, span, points) < 0.0) mesh::mirrorElement(type, span);
    addCell(type, span);
  }

  mesh::UnstructuredMesh build(const std::string& name) const {
    mesh::UnstructuredMesh m = VolumeAssembly::build(name);
    SM_CHECK_EQ(m.invertedFixed, 0u);
    return m;
  }
};

// Corner b of a cell has offsets (b & 1, b >> 1 & 1, b >> 2 & 1).
using Corners = std::array<uint32_t, 8>;

void splitCell(CellList& out, CubeSplit split, const Corners& c, bool oddParity, uint32_t centre) {
  switch (split) {
    case CubeSplit::Hex:
      out.add(CellType::Hex, {c[0], c[1], c[3], c[2], c[4], c[5], c[7], c[6]});
      break;
    case CubeSplit::Tets6:  // Kuhn: the six paths 0 -> 7 along the axes in every order
      for (auto [a, b] : {std::pair{0, 1}, {0, 2}, {1, 0}, {1, 2}, {2, 0}, {2, 1}})
        out.add(CellType::Tet, {c[0], c[1u << a], c[(1u << a) | (1u << b)], c[7]});
      break;
    case CubeSplit::Tets5:
      // A central tetrahedron on four mutually diagonal corners plus the four corners cut off.
      // Neighbouring cells alternate the choice so that their face diagonals agree.
      if (!oddParity) {
        for (const auto& t :
             {Corners{1, 2, 4, 7}, {0, 1, 2, 4}, {3, 1, 2, 7}, {5, 1, 4, 7}, {6, 2, 4, 7}})
          out.add(CellType::Tet, {c[t[0]], c[t[1]], c[t[2]], c[t[3]]});
      } else {
        for (const auto& t :
             {Corners{0, 3, 5, 6}, {1, 0, 3, 5}, {2, 0, 3, 6}, {4, 0, 5, 6}, {7, 3, 5, 6}})
          out.add(CellType::Tet, {c[t[0]], c[t[1]], c[t[2]], c[t[3]]});
      }
      break;
    case CubeSplit::Wedges:  // the xy square cut along its 0-3 diagonal in every cell
      out.add(CellType::Wedge, {c[0], c[1], c[3], c[4], c[5], c[7]});
      out.add(CellType::Wedge, {c[0], c[3], c[2], c[4], c[7], c[6]});
      break;
    case CubeSplit::Pyramids:
      for (const auto& f : {Corners{0, 2, 6, 4},
                            {1, 3, 7, 5},
                            {0, 1, 5, 4},
                            {2, 3, 7, 6},
                            {0, 1, 3, 2},
                            {4, 5, 7, 6}})
        out.add(CellType::Pyramid, {c[f[0]], c[f[1]], c[f[2]], c[f[3]], centre});
      break;
  }
}

const char* splitName(CubeSplit split) {
  switch (split) {
    case CubeSplit::Tets5:
      return "cube-tets5";
    case CubeSplit::Tets6:
      return "cube-tets6";
    case CubeSplit::Wedges:
      return "cube-wedges";
    case CubeSplit::Pyramids:
      return "cube-pyramids";
    case CubeSplit::Hex:
      return "cube-hex";
  }
  return "cube";
}

}  // namespace

mesh::UnstructuredMesh singleElement(CellType type) {
  CellList m;
  switch (type) {
    case CellType::Tet:
      m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
      m.add(type, {0, 1, 2, 3});
      break;
    case CellType::Pyramid:
      m.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}};
      m.add(type, {0, 1, 2, 3, 4});
      break;
    case CellType::Wedge:
      m.points = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {0, 1, 1}, {1, 0, 1}};
      m.add(type, {0, 1, 2, 3, 4, 5});
      break;
    case CellType::Hex:
      m.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                  {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
      m.add(type, {0, 1, 2, 3, 4, 5, 6, 7});
      break;
  }
  return m.build(std::string("single-") + std::string(mesh::cellTypeName(type)));
}

mesh::UnstructuredMesh zoo() {
  CellList m;
  m.points = {{0, 0, 0},        {1, 0, 0},        {1, 1, 0},      {0, 1, 0},  // hexahedron
              {0, 0, 1},        {1, 0, 1},        {1, 1, 1},      {0, 1, 1},  //
              {1.5, 0, 0.5},    {1.5, 1, 0.5},                                // wedge ridge
              {0.5, 0.5, 1.5},                                                // pyramid apex
              {-0.4, 0.5, 1.5}, {1.2, -0.5, 0.5}, {0.5, 1.4, 1.4}};           // tet apexes
  m.add(CellType::Hex, {0, 1, 2, 3, 4, 5, 6, 7});
  m.add(CellType::Wedge, {1, 5, 8, 2, 6, 9});  // on the hexahedron's x = 1 quad
  m.add(CellType::Pyramid, {4, 5, 6, 7, 10});  // on its z = 1 quad
  m.add(CellType::Tet, {4, 7, 10, 11});        // on the pyramid's x = 0 side
  m.add(CellType::Tet, {6, 7, 10, 13});        // on the pyramid's y = 1 side
  m.add(CellType::Tet, {1, 5, 8, 12});         // on the wedge's y = 0 triangle
  return m.build("zoo");
}

std::optional<CubeSplit> cubeSplitNamed(const std::string& name) {
  for (CubeSplit s :
       {CubeSplit::Tets5, CubeSplit::Tets6, CubeSplit::Wedges, CubeSplit::Pyramids, CubeSplit::Hex})
    if (name == splitName(s)) return s;
  return std::nullopt;
}

uint64_t cellsPerCube(CubeSplit split) {
  switch (split) {
    case CubeSplit::Tets5:
      return 5;
    case CubeSplit::Tets6:
    case CubeSplit::Pyramids:
      return 6;
    case CubeSplit::Wedges:
      return 2;
    case CubeSplit::Hex:
      return 1;
  }
  return 0;
}

mesh::UnstructuredMesh cube(CubeSplit split, int n, double size) {
  if (n < 1) throw Error("cube: the number of cells per side must be at least 1, got ", n);
  if (!(size > 0.0)) throw Error("cube: the size must be positive, got ", size);
  const uint64_t side = uint64_t(n) + 1, gridPoints = side * side * side;
  const uint64_t cells = uint64_t(n) * n * n;
  if (gridPoints + (split == CubeSplit::Pyramids ? cells : 0) > 0xFFFFFFFFull)
    throw Error("cube: ", n, " cells per side give more than 2^32 points");
  CellList m;
  const double h = size / n;
  m.points.reserve(gridPoints);
  for (uint64_t k = 0; k < side; ++k)
    for (uint64_t j = 0; j < side; ++j)
      for (uint64_t i = 0; i < side; ++i) m.points.push_back(glm::dvec3(i, j, k) * h);
  auto gridIndex = [&](uint64_t i, uint64_t j, uint64_t k) {
    return uint32_t(i + side * (j + side * k));
  };
  for (uint64_t k = 0; k < uint64_t(n); ++k)
    for (uint64_t j = 0; j < uint64_t(n); ++j)
      for (uint64_t i = 0; i < uint64_t(n); ++i) {
        Corners c;
        for (uint32_t b = 0; b < 8; ++b)
          c[b] = gridIndex(i + (b & 1), j + (b >> 1 & 1), k + (b >> 2 & 1));
        uint32_t centre = 0;
        if (split == CubeSplit::Pyramids) {
          centre = uint32_t(m.points.size());
          m.points.push_back((glm::dvec3(i, j, k) + 0.5) * h);
        }
        splitCell(m, split, c, (i + j + k) % 2 == 1, centre);
      }
  return m.build(splitName(split));
}

}  // namespace sm::gen
