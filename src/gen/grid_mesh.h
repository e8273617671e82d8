// A CFD-like mesh made without a mesher, for any size up to a billion elements: an O-grid around a
// cylinder (radius 1, along z, flow along +x) in a cylindrical far field of radius 15. Next to the
// wall a boundary layer of wedges (hexahedra on the leeward third, x > 0.5), then pyramids where
// the hexahedra meet the tetrahedra, then tetrahedra (six per grid cell, Kuhn's split, so every
// face diagonal agrees between neighbours). Clusters are wavy bands (rings of sectors whose
// boundaries interlock like teeth) plus one cluster nested inside another, as METIS parts of real
// meshes are non-convex and interlock; each cluster is made alone, so memory is bounded by a
// piece, not the mesh (gmsh makes about 14 thousand elements a second; this makes millions).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/unstructured_mesh.h"

namespace sm::gen {

struct GridMeshOptions {
  uint64_t targetElements = 1000000;  // the result is within a few percent (GridMesh::elements)
  int clusters = 0;                   // 0: one per ~4 M elements, at least 8
  int steps = 1;                      // time steps of the analytic fields
};

// What a cell of the grid is split into.
enum class GridCell : uint8_t { Wedges, Hex, Transition, Tets };

class GridMesh {
 public:
  explicit GridMesh(const GridMeshOptions& options);

  uint64_t elements() const { return elements_; }  // exact, over all pieces
  uint64_t points() const;                         // distinct points of the whole mesh
  uint64_t elementsOfType(mesh::CellType t) const { return typeCounts_[mesh::typeIndex(t)]; }
  int clusters() const { return clusters_; }
  int steps() const { return steps_; }
  int nestedCluster() const { return nested_; }  // enclosed by hostCluster(); -1 if none
  int hostCluster() const { return host_; }
  // Grid cells: theta around the cylinder (periodic), radial layers, layers along z.
  int thetaCells() const { return nTheta_; }
  int radialCells() const { return int(radius_.size()) - 1; }
  int zCells() const { return nZ_; }
  int boundaryLayers() const { return nLayers_; }
  mesh::Bounds bounds() const;  // of the whole mesh

  GridCell cellKind(int j, int i) const;  // j radial, i theta
  // The cluster of grid cell (j, i, k), and that of a point (-1 outside the mesh).
  int clusterOfCell(int j, int i, int k) const;
  int clusterAt(const glm::dvec3& p) const;
  // Cluster k alone: its elements, the points they use and the analytic fields over `steps`
  // steps; the same point is bit-identical in every piece that has it.
  mesh::UnstructuredMesh piece(int k) const;
  // The most elements one piece can have (bounds a generator's memory).
  uint64_t largestPieceElements() const;

  glm::dvec3 node(int j, int i, int k) const;

  // Inclusive cell index ranges; i0 may be negative and i1 past nTheta_ (theta wraps), but the
  // range never holds more than nTheta_ cells.
  struct Box {
    int j0, j1, i0, i1, k0, k1;
    bool holds(int j, int i, int k, int nTheta) const;
  };
  Box bubbleBox() const;  // the cells the nested cluster and its shell may take

 private:
  void chooseGrid(uint64_t target);
  void chooseClusters(int clusters);
  uint64_t countElements(std::array<uint64_t, mesh::kNumCellTypes>& perType);
  int bandCluster(int j, int i, int k) const;
  std::vector<Box> candidateBoxes(int cluster) const;
  glm::dvec3 cellCentre(int j, int i, int k) const;
  int radialCellAt(double r) const;
  void reserve(mesh::UnstructuredMesh& m, const std::vector<Box>& boxes) const;

  int nTheta_ = 0, nZ_ = 0, nLayers_ = 0, steps_ = 1;
  std::vector<double> radius_;  // node radii, 1 at the wall
  double zLo_ = -2.0, zHi_ = 2.0;
  uint64_t elements_ = 0;
  std::array<uint64_t, mesh::kNumCellTypes> typeCounts_{};
  std::vector<uint64_t> elementsByLayer_;  // per radial layer (all theta, all z)
  // Clusters: rings (cut at radial layers ringCut_[r] .. ringCut_[r+1]) of sectors, whose
  // boundaries wave by up to ringWave_ layers and sectorWave_ theta cells.
  int clusters_ = 1, nested_ = -1, host_ = -1;
  std::vector<int> ringCut_, ringSectors_, ringFirst_;
  double ringWave_ = 0, sectorWave_ = 0;
  glm::dvec3 bubbleCentre_{0.0};
  double bubbleRadius_ = 0, bubbleShell_ = 0;
};

// Of random lines through the mesh (linesPerCluster through a random point of each band, in random
// directions): how often each crosses a cluster's boundary (entering or leaving it), and whether
// the nested cluster is enclosed by its host alone.
struct ClusterShapeReport {
  int lines = 0;
  double meanCrossings = 0;     // per line and cluster it meets
  int fewestMostCrossings = 0;  // over clusters, the most crossings of any line
  bool nestedEnclosed = false;  // every face neighbour of the nested cluster is its host
};
ClusterShapeReport clusterShapes(const GridMesh& grid, int linesPerCluster = 8, uint64_t seed = 1);

}  // namespace sm::gen
