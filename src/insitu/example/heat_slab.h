// The simulation half of the in-situ example: explicit heat conduction on the nodes of a box grid,
// its cells split into slabs along x, one slab per MPI rank. It knows nothing of shellmarch; it
// only exposes its arrays (points, connectivity, temperature) the way a solver would.
//
// Cells in the lower half of the box are split into six tetrahedra each (Kuhn split about the
// cell's main diagonal), cells in the upper half into two wedges (prisms along z, split by the xy
// diagonal that the tetrahedra use too), so the mesh is conforming across the two halves.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <span>
#include <vector>

namespace heat {

struct Grid {
  int nx = 32, ny = 16, nz = 16;  // cells
  double lx = 2.0, ly = 1.0, lz = 1.0;
};

class HeatSlab {
 public:
  HeatSlab(const Grid& grid, MPI_Comm comm);  // collective
  void step();                                // one explicit step and the halo exchange

  // This rank's mesh: node planes i0 .. i1 (the last plane is shared with the next rank).
  const std::vector<double>& points() const { return points_; }
  const std::vector<int32_t>& tetrahedra() const { return tets_; }
  const std::vector<int32_t>& wedges() const { return wedges_; }
  // Temperature at this rank's mesh vertices, in the order of points(): a view, no copy.
  std::span<const float> temperature() const;
  int steps() const { return steps_; }

 private:
  size_t node(int i, int j, int k) const;  // storage index; i is global, i0 - 1 .. i1 + 1
  float heldValue(double x, double y, double z) const;
  void buildMesh();
  void exchangeHalo();
  std::span<float> plane(int i);

  Grid g_;
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  int i0_ = 0, i1_ = 0;  // this rank owns cells i0 .. i1 - 1
  double h_[3];
  std::vector<float> u_, next_;  // planes i0 - 1 .. i1 + 1 (ghosts at both ends)
  std::vector<int8_t> held_;     // nodes held at a fixed temperature (heater, cooler)
  std::vector<double> points_;
  std::vector<int32_t> tets_, wedges_;
  int steps_ = 0;
};

}  // namespace heat
