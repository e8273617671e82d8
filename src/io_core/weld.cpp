#include "io_core/weld.h"

#include <algorithm>
#include <bit>
#include <cstring>

#include "common/error.h"
#include "common/log.h"
#include "mesh/mesh_builder.h"

namespace sm::io {
namespace {

constexpr uint32_t kEmpty = 0xFFFFFFFFu;

uint64_t hashPoint(const glm::dvec3& p) {
  uint64_t h = std::bit_cast<uint64_t>(p.x) * 0x9E3779B97F4A7C15ull;
  h ^= std::bit_cast<uint64_t>(p.y) + 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
  h ^= std::bit_cast<uint64_t>(p.z) + 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
  h ^= h >> 33;
  h *= 0xFF51AFD7ED558CCDull;
  h ^= h >> 33;
  return h;
}

bool sameBits(const glm::dvec3& a, const glm::dvec3& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Point ids of the welded mesh for every point of every piece, the piece that first had each, and
// where that was in the pieces' points numbered one after another (the mesh's pointOrigin).
struct Welding {
  std::vector<glm::dvec3> points;
  std::vector<uint32_t> firstPiece;
  std::vector<uint32_t> origin;
  std::vector<std::vector<uint32_t>> remap;
};

Welding weldPoints(const std::vector<mesh::UnstructuredMesh>& pieces) {
  uint64_t total = 0;
  for (const auto& p : pieces) total += p.points.size();
  Welding w;
  w.points.reserve(total);
  w.firstPiece.reserve(total);
  w.origin.reserve(total);
  uint32_t pieceStart = 0;
  const uint64_t tableSize = std::bit_ceil(std::max<uint64_t>(2 * total, 16));
  const uint64_t mask = tableSize - 1;
  std::vector<uint32_t> table(tableSize, kEmpty);
  // The last piece that took each welded point: a piece takes a point once, so two coincident
  // points of one piece (a crack, a baffle) stay two even where an earlier piece has the point.
  std::vector<uint32_t> lastPiece;
  lastPiece.reserve(total);
  for (uint32_t k = 0; k < pieces.size(); ++k) {
    const auto& pts = pieces[k].points;
    std::vector<uint32_t>& map = w.remap.emplace_back(pts.size());
    for (size_t i = 0; i < pts.size(); ++i) {
      uint64_t slot = hashPoint(pts[i]) & mask;
      for (;; slot = (slot + 1) & mask) {
        uint32_t e = table[slot];
        if (e == kEmpty) {
          e = static_cast<uint32_t>(w.points.size());
          table[slot] = e;
          w.points.push_back(pts[i]);
          w.firstPiece.push_back(k);
          w.origin.push_back(pieceStart + static_cast<uint32_t>(i));
          lastPiece.push_back(k);
          map[i] = e;
          break;
        }
        if (lastPiece[e] != k && sameBits(w.points[e], pts[i])) {
          lastPiece[e] = k;
          map[i] = e;
          break;
        }
      }
    }
    pieceStart += static_cast<uint32_t>(pts.size());
  }
  return w;
}

bool sameValue(float a, float b) {
  return a == b || (a != a && b != b);
}

void weldFields(const std::string& source, const std::vector<mesh::UnstructuredMesh>& pieces,
                const Welding& w, mesh::UnstructuredMesh& out) {
  for (const mesh::Field& f0 : pieces[0].fields) {
    mesh::Field f{f0.name, std::vector<std::vector<float>>(f0.numSteps())};
    uint64_t disagree = 0;
    for (auto& s : f.steps) s.resize(w.points.size());
    for (uint32_t k = 0; k < pieces.size(); ++k) {
      const mesh::Field* fk = pieces[k].findField(f0.name);
      if (!fk || fk->numSteps() != f0.numSteps())
        throw FileError(source, "piece '", pieces[k].source, "' ",
                        fk ? concat("has ", fk->numSteps(), " time steps of field '", f0.name,
                                    "', the first piece ", f0.numSteps())
                           : concat("has no point field '", f0.name, "'"));
      for (uint64_t s = 0; s < f.steps.size(); ++s) {
        const auto& in = fk->steps[s];
        auto& dst = f.steps[s];
        for (size_t i = 0; i < in.size(); ++i) {
          uint32_t j = w.remap[k][i];
          if (w.firstPiece[j] == k)
            dst[j] = in[i];
          else if (!sameValue(dst[j], in[i]))
            ++disagree;
        }
      }
    }
    if (disagree)
      log::warning(source, ": field '", f.name, "' differs between pieces at ", disagree,
                   " shared points (kept the lower piece's values)");
    out.fields.push_back(std::move(f));
  }
  for (const auto& p : pieces)
    if (p.fields.size() != pieces[0].fields.size())
      throw FileError(source, "piece '", p.source, "' has ", p.fields.size(),
                      " point fields, the first piece ", pieces[0].fields.size());
}

// Cell fields follow the cells: per type, piece after piece, as the cells are joined below.
void joinCellFields(const std::string& source, std::vector<mesh::UnstructuredMesh>& pieces,
                    mesh::UnstructuredMesh& out) {
  for (size_t f = 0; f < pieces[0].cellFields.size(); ++f) {
    mesh::CellField joined{pieces[0].cellFields[f].name, {}};
    joined.steps.resize(pieces[0].cellFields[f].steps.size());
    for (auto& p : pieces) {
      if (p.cellFields.size() != pieces[0].cellFields.size() ||
          p.cellFields[f].name != joined.name ||
          p.cellFields[f].steps.size() != joined.steps.size())
        throw FileError(source, "piece '", p.source, "' does not have the cell data '", joined.name,
                        "' with the first piece's time steps");
      for (size_t s = 0; s < joined.steps.size(); ++s)
        for (int t = 0; t < mesh::kNumCellTypes; ++t) {
          auto& in = p.cellFields[f].steps[s][t];
          joined.steps[s][t].insert(joined.steps[s][t].end(), in.begin(), in.end());
          std::vector<float>().swap(in);
        }
    }
    out.cellFields.push_back(std::move(joined));
  }
}

// Cell origins follow the cells too, each piece's numbered after the cells of the pieces before it
// (as readCellFieldStep numbers the values of the pieces it reads). A reader asked for origins
// gives every piece its own; otherwise only pieces with polyhedra have them (so that a
// polyhedron's tetrahedra count once at a point: mesh::cellUsesAtPoints), and the other pieces'
// elements are numbered in their order, which tells cells apart as well but does not say where
// in the file each was (such a mesh is not read step by step by origin).
void joinCellOrigins(const std::vector<mesh::UnstructuredMesh>& pieces,
                     mesh::UnstructuredMesh& out) {
  auto hasOrigins = [](const mesh::UnstructuredMesh& p) {
    return p.cellOrigin.size() == p.numCells() && (p.numCells() > 0 || p.fileCells > 0);
  };
  if (std::none_of(pieces.begin(), pieces.end(), hasOrigins)) return;
  auto span = [&](const mesh::UnstructuredMesh& p) {
    return hasOrigins(p) ? p.fileCells : p.numCells();
  };
  uint64_t total = 0;
  for (const auto& p : pieces) total += span(p);
  if (total > 0xFFFFFFFFull)
    throw FileError(out.source, "the pieces read hold ", total,
                    " cells: cell origins are 32-bit, so at most ", 0xFFFFFFFFull,
                    " can be kept (use more ranks)");
  out.fileCells = total;
  for (int t = 0; t < mesh::kNumCellTypes; ++t) {
    uint64_t offset = 0;
    for (const auto& p : pieces) {
      uint64_t first = 0;  // p's elements of the types before t
      for (int u = 0; u < t; ++u) first += p.numCells(mesh::kAllCellTypes[u]);
      const uint64_t n = p.numCells(mesh::kAllCellTypes[t]);
      const bool own = hasOrigins(p);
      for (uint64_t i = first; i < first + n; ++i)
        out.cellOrigin.push_back(uint32_t(offset + (own ? p.cellOrigin[i] : i)));
      offset += span(p);
    }
  }
}

}  // namespace

mesh::UnstructuredMesh weldPieces(const std::string& source,
                                  std::vector<mesh::UnstructuredMesh> pieces) {
  mesh::UnstructuredMesh out;
  out.source = source;
  if (pieces.empty()) return out;
  uint64_t total = 0;
  for (const auto& p : pieces) total += p.points.size();
  // Checked before the welding, whose point origins and piece starts are 32-bit.
  mesh::checkPointCount(source, total, "the pieces read hold", "use more ranks");
  Welding w = weldPoints(pieces);
  weldFields(source, pieces, w, out);
  joinCellFields(source, pieces, out);
  joinCellOrigins(pieces, out);
  for (auto& p : pieces) {  // no longer needed: free them before the cells are copied
    std::vector<glm::dvec3>().swap(p.points);
    std::vector<mesh::Field>().swap(p.fields);
  }
  for (int t = 0; t < mesh::kNumCellTypes; ++t) {
    uint64_t n = 0;
    for (const auto& p : pieces) n += p.cells[t].size();
    out.cells[t].reserve(n);
    out.clusters[t].reserve(n / mesh::numVerts(mesh::kAllCellTypes[t]));
    // Each piece's cells are freed once copied: the welded arrays grow as the pieces' shrink, so
    // the cells are not held twice (preparation's peak memory is measured against its output).
    for (uint32_t k = 0; k < pieces.size(); ++k) {
      for (uint32_t id : pieces[k].cells[t]) out.cells[t].push_back(w.remap[k][id]);
      out.clusters[t].insert(out.clusters[t].end(), pieces[k].clusters[t].begin(),
                             pieces[k].clusters[t].end());
      std::vector<uint32_t>().swap(pieces[k].cells[t]);
      std::vector<int32_t>().swap(pieces[k].clusters[t]);
    }
  }
  for (auto& p : pieces) {
    out.skipped.add(p.skipped);
    out.invertedFixed += p.invertedFixed;
    if (out.timeValues.empty()) out.timeValues = std::move(p.timeValues);
    if (out.cellArrays.empty()) out.cellArrays = std::move(p.cellArrays);
  }
  out.points = std::move(w.points);
  out.pointOrigin = std::move(w.origin);
  return out;
}

}  // namespace sm::io
