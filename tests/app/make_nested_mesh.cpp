// make_nested_mesh OUT.pvtu
// The unit cube as 6^3 cells split into tetrahedra, in three clusters nested like an onion: a core
// (the middle 2^3 cells), a hollow shell around it, and a hollow outer shell. Each shell encloses
// the clusters inside it, so a ray crosses the outer cluster twice with the others in between: the
// case that single-fragment (IceT-style) compositing gets wrong and deep compositing must get
// right.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>

#include "gen/generate.h"
#include "io/mesh_io.h"

using namespace sm;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_nested_mesh OUT.pvtu\n");
    return 2;
  }
  try {
    mesh::UnstructuredMesh m = gen::cube(gen::CubeSplit::Tets6, 6);
    for (mesh::CellType type : mesh::kAllCellTypes) {
      const uint32_t t = mesh::typeIndex(type), n = mesh::numVerts(type);
      auto& ids = m.clusters[t];
      ids.assign(m.cells[t].size() / n, 0);
      for (size_t e = 0; e < ids.size(); ++e) {
        glm::dvec3 c(0.0);
        for (uint32_t i = 0; i < n; ++i) c += m.points[m.cells[t][e * n + i]];
        c /= double(n);
        double d = std::max({std::abs(c.x - 0.5), std::abs(c.y - 0.5), std::abs(c.z - 0.5)});
        ids[e] = d < 1.0 / 6 ? 0 : d < 1.0 / 3 ? 1 : 2;
      }
    }
    gen::addAnalyticFields(m, 1);
    io::writePvtu(argv[1], m);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_nested_mesh: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
