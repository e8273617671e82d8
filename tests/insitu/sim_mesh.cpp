#include "sim_mesh.h"

#include <algorithm>
#include <numeric>
#include <random>

namespace sm::insitu::test {

std::vector<float> SimMesh::field(const std::function<float(glm::dvec3)>& f) const {
  std::vector<float> v(vertices());
  for (size_t i = 0; i < v.size(); ++i) v[i] = f(point(i));
  return v;
}

SimMesh simMesh(const mesh::UnstructuredMesh& m) {
  SimMesh s;
  for (const glm::dvec3& p : m.points) s.xyz.insert(s.xyz.end(), {p.x, p.y, p.z});
  for (int t = 0; t < mesh::kNumCellTypes; ++t)
    s.cells[t].assign(m.cells[t].begin(), m.cells[t].end());
  return s;
}

SimMesh shuffled(const SimMesh& s, uint32_t seed) {
  std::vector<int64_t> order(s.vertices());  // new position -> old vertex
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(seed));
  std::vector<int64_t> newId(order.size());
  SimMesh out;
  for (size_t i = 0; i < order.size(); ++i) {
    newId[order[i]] = int64_t(i);
    const glm::dvec3 p = s.point(order[i]);
    out.xyz.insert(out.xyz.end(), {p.x, p.y, p.z});
  }
  for (int t = 0; t < 4; ++t)
    for (int64_t v : s.cells[t]) out.cells[t].push_back(newId[v]);
  return out;
}

namespace {

// The elements of m that `keep` accepts (type index, element index), with only their vertices.
SimMesh subset(const mesh::UnstructuredMesh& m, const std::function<bool(int, size_t)>& keep) {
  SimMesh out;
  std::vector<int64_t> newId(m.numPoints(), -1);
  for (mesh::CellType type : mesh::kAllCellTypes) {
    const uint32_t nv = mesh::numVerts(type), t = mesh::typeIndex(type);
    for (size_t e = 0; e + nv <= m.cells[t].size(); e += nv) {
      if (!keep(int(t), e / nv)) continue;
      for (uint32_t k = 0; k < nv; ++k) {
        int64_t& id = newId[m.cells[t][e + k]];
        if (id < 0) {
          id = int64_t(out.vertices());
          const glm::dvec3& p = m.points[m.cells[t][e + k]];
          out.xyz.insert(out.xyz.end(), {p.x, p.y, p.z});
          out.ids.push_back(int64_t(m.cells[t][e + k]));
        }
        out.cells[t].push_back(id);
      }
    }
  }
  return out;
}

}  // namespace

namespace {

double centroidX(const mesh::UnstructuredMesh& m, int t, size_t e) {
  const uint32_t nv = mesh::numVerts(mesh::kAllCellTypes[t]);
  double x = 0;
  for (uint32_t k = 0; k < nv; ++k) x += m.points[m.cells[t][e * nv + k]].x / nv;
  return x;
}

}  // namespace

SimMesh slabWithIds(const mesh::UnstructuredMesh& m, double lo, double hi) {
  return subset(m, [&](int t, size_t e) {
    const double x = centroidX(m, t, e);
    return x >= lo && x < hi;
  });
}

SimMesh slab(const mesh::UnstructuredMesh& m, double lo, double hi) {
  SimMesh s = slabWithIds(m, lo, hi);
  s.ids.clear();
  return s;
}

mesh::UnstructuredMesh baffled(const mesh::UnstructuredMesh& m, double at) {
  mesh::UnstructuredMesh out = m;
  std::vector<int64_t> copyOf(m.numPoints(), -1);
  for (int t = 0; t < mesh::kNumCellTypes; ++t) {
    const uint32_t nv = mesh::numVerts(mesh::kAllCellTypes[t]);
    for (size_t e = 0; e * nv < m.cells[t].size(); ++e) {
      if (centroidX(m, t, e) < at) continue;
      for (uint32_t k = 0; k < nv; ++k) {
        uint32_t& v = out.cells[t][e * nv + k];
        if (m.points[v].x != at) continue;
        if (copyOf[v] < 0) {
          copyOf[v] = int64_t(out.points.size());
          out.points.push_back(m.points[v]);
        }
        v = uint32_t(copyOf[v]);
      }
    }
  }
  return out;
}

SimMesh dealt(const mesh::UnstructuredMesh& m, int part, int parts) {
  return subset(m, [&](int t, size_t e) {
    const uint64_t i = e + 7919u * uint64_t(t);
    return int(((i * 0x9E3779B97F4A7C15ull) >> 40) % uint64_t(parts)) == part;
  });
}

std::vector<float> cellField(const SimMesh& s, const std::function<float(glm::dvec3)>& f) {
  std::vector<float> values;
  for (int t = 0; t < 4; ++t) {
    const uint32_t nv = mesh::numVerts(mesh::kAllCellTypes[t]);
    for (size_t e = 0; e < s.cells[t].size(); e += nv) {
      glm::dvec3 c(0.0);
      for (uint32_t k = 0; k < nv; ++k) c += s.point(size_t(s.cells[t][e + k])) / double(nv);
      values.push_back(f(c));
    }
  }
  return values;
}

}  // namespace sm::insitu::test
