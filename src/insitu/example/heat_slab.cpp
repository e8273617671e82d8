#include "heat_slab.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace heat {
namespace {

double sq(double v) {
  return v * v;
}

}  // namespace

HeatSlab::HeatSlab(const Grid& grid, MPI_Comm comm) : g_(grid), comm_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  if (g_.nx < size_ || g_.ny < 1 || g_.nz < 2)
    throw std::invalid_argument("heat: the grid needs nx >= ranks, ny >= 1, nz >= 2");
  // Slabs of nearly equal cell counts; each rank has at least one.
  i0_ = int(int64_t(g_.nx) * rank_ / size_);
  i1_ = int(int64_t(g_.nx) * (rank_ + 1) / size_);
  h_[0] = g_.lx / g_.nx;
  h_[1] = g_.ly / g_.ny;
  h_[2] = g_.lz / g_.nz;
  const size_t count = size_t(i1_ - i0_ + 3) * (g_.ny + 1) * (g_.nz + 1);
  u_.assign(count, 0.0f);
  held_.assign(count, 0);
  for (int i = i0_ - 1; i <= i1_ + 1; ++i)
    for (int j = 0; j <= g_.ny; ++j)
      for (int k = 0; k <= g_.nz; ++k) {
        float v = heldValue(i * h_[0], j * h_[1], k * h_[2]);
        if (v != 0.0f) u_[node(i, j, k)] = v, held_[node(i, j, k)] = 1;
      }
  next_ = u_;
  exchangeHalo();  // fills the mirrored ghost planes at both ends of the box
  buildMesh();
}

size_t HeatSlab::node(int i, int j, int k) const {
  return (size_t(i - (i0_ - 1)) * (g_.ny + 1) + j) * (g_.nz + 1) + k;
}

std::span<float> HeatSlab::plane(int i) {
  return std::span<float>(u_).subspan(node(i, 0, 0), size_t(g_.ny + 1) * (g_.nz + 1));
}

// A heater low in the box and a cooler high up on the other side.
float HeatSlab::heldValue(double x, double y, double z) const {
  const double r2 = sq(0.12 * g_.lx);
  if (sq(x - 0.3 * g_.lx) + sq(y - 0.5 * g_.ly) + sq(z - 0.3 * g_.lz) < r2) return 1.0f;
  if (sq(x - 0.7 * g_.lx) + sq(y - 0.5 * g_.ly) + sq(z - 0.75 * g_.lz) < r2) return -1.0f;
  return 0.0f;
}

void HeatSlab::buildMesh() {
  for (int i = i0_; i <= i1_; ++i)
    for (int j = 0; j <= g_.ny; ++j)
      for (int k = 0; k <= g_.nz; ++k) {
        points_.push_back(i * h_[0]);
        points_.push_back(j * h_[1]);
        points_.push_back(k * h_[2]);
      }
  // Vertex ids are storage indices relative to plane i0, so temperature() is a plain view.
  const size_t base = node(i0_, 0, 0);
  for (int i = i0_; i < i1_; ++i)
    for (int j = 0; j < g_.ny; ++j)
      for (int k = 0; k < g_.nz; ++k) {
        auto c = [&](int dx, int dy, int dz) {
          return int32_t(node(i + dx, j + dy, k + dz) - base);
        };
        if (k < g_.nz / 2) {
          // Kuhn split: paths from corner 000 to 111 along the axes in every order. Odd
          // permutations swap two vertices so that every tetrahedron has positive volume.
          static const int order[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                          {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
          for (int p = 0; p < 6; ++p) {
            int d1[3] = {0, 0, 0}, d2[3];
            d1[order[p][0]] = 1;
            std::copy(d1, d1 + 3, d2);
            d2[order[p][1]] = 1;
            int32_t a = c(d1[0], d1[1], d1[2]), b = c(d2[0], d2[1], d2[2]);
            if (p >= 3) std::swap(a, b);
            tets_.insert(tets_.end(), {c(0, 0, 0), a, b, c(1, 1, 1)});
          }
        } else {
          // Two prisms split by the diagonal 00-11, base triangle first (VTK: the base's normal
          // points away from the top triangle, so the base runs clockwise seen from above).
          wedges_.insert(wedges_.end(),
                         {c(0, 0, 0), c(1, 1, 0), c(1, 0, 0), c(0, 0, 1), c(1, 1, 1), c(1, 0, 1)});
          wedges_.insert(wedges_.end(),
                         {c(0, 0, 0), c(0, 1, 0), c(1, 1, 0), c(0, 0, 1), c(0, 1, 1), c(1, 1, 1)});
        }
      }
}

std::span<const float> HeatSlab::temperature() const {
  return std::span<const float>(u_).subspan(node(i0_, 0, 0), points_.size() / 3);
}

void HeatSlab::step() {
  // Stable for r <= 1/6 per axis (forward Euler); insulated walls by mirroring.
  const double r = 0.15;
  const int iEnd = rank_ == size_ - 1 ? i1_ : i1_ - 1;  // the last plane belongs to the next rank
  for (int i = i0_; i <= iEnd; ++i)
    for (int j = 0; j <= g_.ny; ++j)
      for (int k = 0; k <= g_.nz; ++k) {
        const size_t n = node(i, j, k);
        if (held_[n]) continue;
        const int jm = j > 0 ? j - 1 : 1, jp = j < g_.ny ? j + 1 : g_.ny - 1;
        const int km = k > 0 ? k - 1 : 1, kp = k < g_.nz ? k + 1 : g_.nz - 1;
        const float lap = u_[node(i - 1, j, k)] + u_[node(i + 1, j, k)] + u_[node(i, jm, k)] +
                          u_[node(i, jp, k)] + u_[node(i, j, km)] + u_[node(i, j, kp)] -
                          6.0f * u_[n];
        next_[n] = u_[n] + float(r) * lap;
      }
  for (int i = i0_; i <= iEnd; ++i) {
    auto from = std::span<const float>(next_).subspan(node(i, 0, 0), plane(i).size());
    std::copy(from.begin(), from.end(), plane(i).begin());
  }
  exchangeHalo();
  ++steps_;
}

void HeatSlab::exchangeHalo() {
  const int left = rank_ > 0 ? rank_ - 1 : MPI_PROC_NULL;
  const int right = rank_ < size_ - 1 ? rank_ + 1 : MPI_PROC_NULL;
  const int n = int(plane(i0_).size());
  // My first plane is the left rank's last (shared) plane; my last owned plane is the right
  // rank's ghost.
  MPI_Sendrecv(plane(i0_).data(), n, MPI_FLOAT, left, 0, plane(i1_).data(), n, MPI_FLOAT, right, 0,
               comm_, MPI_STATUS_IGNORE);
  MPI_Sendrecv(plane(i1_ - 1).data(), n, MPI_FLOAT, right, 1, plane(i0_ - 1).data(), n, MPI_FLOAT,
               left, 1, comm_, MPI_STATUS_IGNORE);
  // Insulated ends: the ghost plane mirrors the plane inside.
  if (left == MPI_PROC_NULL) std::ranges::copy(plane(1), plane(-1).begin());
  if (right == MPI_PROC_NULL) std::ranges::copy(plane(g_.nx - 1), plane(g_.nx + 1).begin());
}

}  // namespace heat
