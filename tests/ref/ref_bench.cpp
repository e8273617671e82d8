// Not a test: times the reference renderer (BVH build, Grid and Converged renders) on cubes of
// about 100 k elements of each split, and the BVH build on about a million tetrahedra.
//   ref_bench [size=128] [threads=0]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "ref/reference_renderer.h"
#include "test_meshes.h"

namespace {

using namespace sm;
using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

void bench(ref::test::Split split, int n, int size, unsigned threads) {
  auto m = ref::test::cubeMesh(split, n);
  auto values = ref::test::pointField(m, [](const glm::dvec3& p) {
    return p.x + 2 * p.y + 3 * p.z + 0.5 * std::sin(12 * p.x) * std::cos(9 * p.y);
  });
  auto start = Clock::now();
  ref::ReferenceRenderer r(m);
  double build = seconds(start);
  auto tf = scene::makeTransferFunction("viridis");
  tf.lo = -0.5;
  tf.hi = 6.5;
  tf.opacityScale = 4.0;
  auto camera = scene::frameBounds(m.bounds(), scene::ViewPreset::Iso, 1.0);
  std::printf("%-9s %8lu elements  build %.3f s", ref::test::splitName(split).c_str(),
              (unsigned long)m.numCells(), build);
  for (ref::RenderMode mode : {ref::RenderMode::Grid, ref::RenderMode::Converged}) {
    ref::RenderSettings settings{.dt = 1.0 / 512, .mode = mode, .threads = threads};
    start = Clock::now();
    auto result = r.render(camera, size, size, values, tf, settings);
    double t = seconds(start);
    uint64_t samples = 0, crossings = 0;
    for (const auto& s : result.stats) samples += s.samples, crossings += s.crossings;
    std::printf("  | %s %.2f s (%.0f crossings, %.0f samples per pixel)",
                mode == ref::RenderMode::Grid ? "grid" : "converged", t,
                double(crossings) / result.stats.size(), double(samples) / result.stats.size());
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  int size = argc > 1 ? std::atoi(argv[1]) : 128;
  unsigned threads = argc > 2 ? unsigned(std::atoi(argv[2])) : 0;
  using ref::test::Split;
  bench(Split::Tets6, 26, size, threads);
  bench(Split::Tets5, 28, size, threads);
  bench(Split::Pyramids, 26, size, threads);
  bench(Split::Wedges, 37, size, threads);
  bench(Split::Hex, 47, size, threads);
  auto big = ref::test::cubeMesh(Split::Tets6, 55);
  auto start = Clock::now();
  ref::ReferenceRenderer r(big);
  std::printf("BVH build for %lu tetrahedra: %.2f s\n", (unsigned long)big.numCells(),
              seconds(start));
  return 0;
}
