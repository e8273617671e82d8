#include "support/test_meshes.h"

#include "mesh/mesh_builder.h"

namespace sm::test {
namespace {

mesh::MeshBuilder gridPoints(int n, double size, glm::dvec3 offset) {
  mesh::MeshBuilder b("grid");
  std::vector<glm::dvec3> pts;
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) pts.push_back(offset + glm::dvec3(i, j, k) * (size / n));
  b.setPoints(std::move(pts));
  return b;
}

template <typename Fn>
void forEachCell(int n, Fn&& fn) {
  auto id = [n](int i, int j, int k) { return int64_t(i + (n + 1) * (j + (n + 1) * k)); };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int64_t c[8] = {
            id(i, j, k),     id(i + 1, j, k),     id(i + 1, j + 1, k),     id(i, j + 1, k),
            id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
        fn(i, c);
      }
}

}  // namespace

mesh::UnstructuredMesh hexGrid(int n, double size, glm::dvec3 offset, int clusters) {
  auto b = gridPoints(n, size, offset);
  uint64_t cell = 0;
  forEachCell(n, [&](int i, const int64_t* c) { b.addVtkCell(12, {c, 8}, cell++, i % clusters); });
  return b.finish();
}

mesh::UnstructuredMesh kuhnTetGrid(int n, double size, glm::dvec3 offset, int clusters) {
  auto b = gridPoints(n, size, offset);
  // Six tets sharing the diagonal 0-6; conforming because every cell uses the same diagonal
  // direction, so the face diagonals of neighbouring cells agree.
  static const int kTets[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                                  {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
  uint64_t cell = 0;
  forEachCell(n, [&](int i, const int64_t* c) {
    for (const auto& t : kTets) {
      const int64_t ids[4] = {c[t[0]], c[t[1]], c[t[2]], c[t[3]]};
      b.addVtkCell(10, ids, cell++, i % clusters);
    }
  });
  return b.finish();
}

mesh::UnstructuredMesh wedgeGrid(int n, double size) {
  auto b = gridPoints(n, size, glm::dvec3(0.0));
  uint64_t cell = 0;
  forEachCell(n, [&](int, const int64_t* c) {
    const int64_t w0[6] = {c[0], c[1], c[2], c[4], c[5], c[6]};
    const int64_t w1[6] = {c[0], c[2], c[3], c[4], c[6], c[7]};
    b.addVtkCell(13, w0, cell++);
    b.addVtkCell(13, w1, cell++);
  });
  return b.finish();
}

mesh::UnstructuredMesh pyramidGrid(int n, double size) {
  std::vector<glm::dvec3> pts;
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) pts.push_back(glm::dvec3(i, j, k) * (size / n));
  const int64_t corners = int64_t(pts.size());
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) pts.push_back((glm::dvec3(i, j, k) + 0.5) * (size / n));
  mesh::MeshBuilder b("pyramid-grid");
  b.setPoints(std::move(pts));
  // Cube faces as quads (local corner ids), each the base of a pyramid to the centre.
  static const int kFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                   {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  uint64_t cell = 0;
  int64_t centre = corners;
  forEachCell(n, [&](int, const int64_t* c) {
    for (const auto& f : kFaces) {
      const int64_t ids[5] = {c[f[0]], c[f[1]], c[f[2]], c[f[3]], centre};
      b.addVtkCell(14, ids, cell++);
    }
    ++centre;
  });
  return b.finish();
}

glm::dvec3 cellCentroid(const mesh::UnstructuredMesh& m, int t, size_t e) {
  const uint32_t nv = mesh::numVerts(mesh::kAllCellTypes[t]);
  glm::dvec3 c(0.0);
  for (uint32_t k = 0; k < nv; ++k) c += m.points[m.cells[t][e * nv + k]];
  return c / double(nv);
}

mesh::UnstructuredMesh makeTestMesh(int n, int clusters) {
  mesh::MeshBuilder b("test mesh");
  std::vector<glm::dvec3> pts;
  auto grid = [n](int i, int j, int k) { return int64_t((k * (n + 1) + j) * (n + 1) + i); };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        pts.push_back(glm::dvec3(i, j, k) * 0.1 + glm::dvec3(1e3, -2, 0.5));
  struct Cube {
    int i, j, k;
  };
  std::vector<Cube> withCentre;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if ((i + j + k) % 4 == 3) {
          withCentre.push_back({i, j, k});
          pts.push_back((glm::dvec3(i, j, k) + 0.5) * 0.1 + glm::dvec3(1e3, -2, 0.5));
        }
  b.setPoints(pts);
  uint64_t fileCell = 0, centre = uint64_t(n + 1) * (n + 1) * (n + 1);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int64_t v[8] = {grid(i, j, k),
                              grid(i + 1, j, k),
                              grid(i + 1, j + 1, k),
                              grid(i, j + 1, k),
                              grid(i, j, k + 1),
                              grid(i + 1, j, k + 1),
                              grid(i + 1, j + 1, k + 1),
                              grid(i, j + 1, k + 1)};
        const int32_t cl = int32_t(int64_t(i) * clusters / n);
        auto add = [&](mesh::CellType t, std::initializer_list<int> local, int64_t extra = -1) {
          int64_t ids[8];
          size_t c = 0;
          for (int l : local) ids[c++] = v[l];
          if (extra >= 0) ids[c++] = extra;
          b.addCell(t, {ids, c}, fileCell++, cl);
        };
        switch ((i + j + k) % 4) {
          case 0:
            add(mesh::CellType::Hex, {0, 1, 2, 3, 4, 5, 6, 7});
            break;
          case 1:
            add(mesh::CellType::Wedge, {0, 1, 2, 4, 5, 6});
            add(mesh::CellType::Wedge, {0, 2, 3, 4, 6, 7});
            break;
          case 2:
            for (auto t : {std::initializer_list<int>{0, 1, 2, 6},
                           {0, 2, 3, 6},
                           {0, 3, 7, 6},
                           {0, 7, 4, 6},
                           {0, 4, 5, 6},
                           {0, 5, 1, 6}})
              add(mesh::CellType::Tet, t);
            break;
          default: {
            const int64_t c = int64_t(centre++);
            for (auto f : {std::initializer_list<int>{0, 1, 2, 3},
                           {4, 5, 6, 7},
                           {0, 1, 5, 4},
                           {1, 2, 6, 5},
                           {2, 3, 7, 6},
                           {3, 0, 4, 7}})
              add(mesh::CellType::Pyramid, f, c);
          }
        }
      }
  std::vector<float> f(pts.size()), g0(pts.size()), g1(pts.size());
  for (size_t p = 0; p < pts.size(); ++p) {
    f[p] = float(pts[p].x - 1e3 + 2 * pts[p].y);
    g0[p] = float(p % 97);
    g1[p] = float(p) * 0.5f;
  }
  b.addFieldStep("f", 0, f);
  b.addFieldStep("g", 0, g0);
  b.addFieldStep("g", 1, g1);
  b.setTimeValues({0.0, 1.0});
  return b.finish();
}

}  // namespace sm::test
