// .vtu writer (pvtu_writer.cpp writes pieces and series with it): appended raw data with a UInt64
// header, optionally zlib-compressed in blocks (compressed in parallel), Float64 points, Int64
// connectivity and offsets, UInt8 types, Int32 cluster ids, Float32 fields (NAME@t<K> per step when
// a field has several), Float64 TimeValues field data. Array bytes are produced block by block from
// the mesh, never as one converted copy of the whole mesh.
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>

#include "common/check.h"
#include "common/error.h"
#include "common/file_util.h"
#include "io/mesh_io.h"
#include "io/vtk_binary.h"
#include "io/vtk_xml_names.h"
#include "io_core/array_plan.h"

namespace sm::io {
namespace {

constexpr uint64_t kBlockSize = 1 << 20;  // a multiple of every element size
constexpr int kZlibLevel = 1;             // simulation data gains little from slower levels

using Fill = std::function<void(uint64_t firstByte, uint64_t bytes, uint8_t* dst)>;

struct OutArray {
  std::string parent;  // FieldData, PointData, CellData, Points or Cells
  std::string attributes;
  uint64_t bytes = 0;
  Fill fill;
  std::vector<uint8_t> compressed;  // header and blocks, when compressing
  uint64_t encodedSize = 0;
};

// An array of `count` values of T; fill(first, n, out) writes values [first, first + n).
template <class T>
OutArray makeArray(std::string parent, std::string attributes, uint64_t count,
                   std::function<void(uint64_t, uint64_t, T*)> fill) {
  OutArray a{std::move(parent), std::move(attributes), count * sizeof(T), {}, {}, 0};
  a.fill = [fill = std::move(fill)](uint64_t b, uint64_t n, uint8_t* dst) {
    fill(b / sizeof(T), n / sizeof(T), reinterpret_cast<T*>(dst));
  };
  return a;
}

// Cells of all types as one list in type order (tetrahedra, pyramids, wedges, hexahedra).
struct CellRanges {
  uint64_t firstCell[mesh::kNumCellTypes + 1] = {};
  uint64_t firstId[mesh::kNumCellTypes + 1] = {};
  explicit CellRanges(const mesh::UnstructuredMesh& m) {
    for (int t = 0; t < mesh::kNumCellTypes; ++t) {
      firstCell[t + 1] = firstCell[t] + m.numCells(mesh::kAllCellTypes[t]);
      firstId[t + 1] = firstId[t] + m.cells[t].size();
    }
  }
  int typeOfCell(uint64_t c) const {
    int t = 0;
    while (c >= firstCell[t + 1]) ++t;
    return t;
  }
  int typeOfId(uint64_t i) const {
    int t = 0;
    while (i >= firstId[t + 1]) ++t;
    return t;
  }
};

void addCellArrays(std::vector<OutArray>& out, const mesh::UnstructuredMesh& m) {
  auto r = std::make_shared<CellRanges>(m);
  const uint64_t nCells = r->firstCell[mesh::kNumCellTypes], nIds = r->firstId[mesh::kNumCellTypes];
  out.push_back(makeArray<int64_t>("Cells", dataArray("Int64", "connectivity"), nIds,
                                   [&m, r](uint64_t b, uint64_t n, int64_t* o) {
                                     for (uint64_t i = b; i < b + n; ++i) {
                                       int t = r->typeOfId(i);
                                       o[i - b] = m.cells[t][i - r->firstId[t]];
                                     }
                                   }));
  out.push_back(makeArray<int64_t>(
      "Cells", dataArray("Int64", "offsets"), nCells, [r](uint64_t b, uint64_t n, int64_t* o) {
        for (uint64_t c = b; c < b + n; ++c) {
          int t = r->typeOfCell(c);
          uint64_t nv = mesh::numVerts(mesh::kAllCellTypes[t]);
          o[c - b] = int64_t(r->firstId[t] + (c - r->firstCell[t] + 1) * nv);
        }
      }));
  out.push_back(makeArray<uint8_t>(
      "Cells", dataArray("UInt8", "types"), nCells, [r](uint64_t b, uint64_t n, uint8_t* o) {
        for (uint64_t c = b; c < b + n; ++c)
          o[c - b] = uint8_t(mesh::toVtkType(mesh::kAllCellTypes[r->typeOfCell(c)]));
      }));
  out.push_back(makeArray<int32_t>("CellData", dataArray("Int32", "cluster"), nCells,
                                   [&m, r](uint64_t b, uint64_t n, int32_t* o) {
                                     for (uint64_t c = b; c < b + n; ++c) {
                                       int t = r->typeOfCell(c);
                                       o[c - b] = m.clusters[t][c - r->firstCell[t]];
                                     }
                                   }));
  // Cell data, written in the cells' order (type after type), one array per step.
  for (const mesh::CellField& f : m.cellFields)
    for (uint64_t s = 0; s < f.steps.size(); ++s) {
      const auto* perType = &f.steps[s];
      for (int t = 0; t < mesh::kNumCellTypes; ++t)
        SM_CHECK_EQ((*perType)[t].size(), m.numCells(mesh::kAllCellTypes[t]));
      out.push_back(makeArray<float>("CellData", dataArray("Float32", arrayName(f, s)), nCells,
                                     [perType, r](uint64_t b, uint64_t n, float* o) {
                                       for (uint64_t c = b; c < b + n; ++c) {
                                         int t = r->typeOfCell(c);
                                         o[c - b] = (*perType)[t][c - r->firstCell[t]];
                                       }
                                     }));
    }
}

std::vector<OutArray> meshArrays(const mesh::UnstructuredMesh& m) {
  std::vector<OutArray> out;
  if (!m.timeValues.empty()) {
    OutArray t = makeArray<double>("FieldData", dataArray("Float64", "TimeValues"),
                                   m.timeValues.size(), [&m](uint64_t b, uint64_t n, double* o) {
                                     std::memcpy(o, m.timeValues.data() + b, n * sizeof(double));
                                   });
    t.attributes += concat(" NumberOfTuples=\"", m.timeValues.size(), "\"");
    out.push_back(std::move(t));
  }
  for (const mesh::Field& f : m.fields) {
    for (uint64_t s = 0; s < f.numSteps(); ++s) {
      SM_CHECK_EQ(f.steps[s].size(), m.points.size());
      const std::string name = arrayName(f, s);
      const std::vector<float>* v = &f.steps[s];
      out.push_back(makeArray<float>("PointData", dataArray("Float32", name), v->size(),
                                     [v](uint64_t b, uint64_t n, float* o) {
                                       std::memcpy(o, v->data() + b, n * sizeof(float));
                                     }));
    }
  }
  out.push_back(makeArray<double>("Points", dataArray("Float64", "Points", 3), 3 * m.points.size(),
                                  [&m](uint64_t b, uint64_t n, double* o) {
                                    std::memcpy(o, &m.points[0].x + b, n * sizeof(double));
                                  }));
  addCellArrays(out, m);
  return out;
}

std::string xmlHeader(const mesh::UnstructuredMesh& m, const std::vector<OutArray>& arrays,
                      bool compress) {
  std::string x = concat(
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"",
      std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian",
      "\" header_type=\"UInt64\"", compress ? " compressor=\"vtkZLibDataCompressor\"" : "",
      ">\n  <UnstructuredGrid>\n");
  uint64_t offset = 0;
  auto section = [&](const std::string& parent, const std::string& indent) {
    std::string s;
    for (const OutArray& a : arrays) {
      if (a.parent == parent)
        s += concat(indent, "<DataArray ", a.attributes, " format=\"appended\" offset=\"", offset,
                    "\"/>\n");
      if (a.parent == parent) offset += a.encodedSize;
    }
    return s;
  };
  std::string fd = section("FieldData", "      ");
  if (!fd.empty()) x += "    <FieldData>\n" + fd + "    </FieldData>\n";
  x += concat("    <Piece NumberOfPoints=\"", m.points.size(), "\" NumberOfCells=\"", m.numCells(),
              "\">\n");
  x += "      <PointData>\n" + section("PointData", "        ") + "      </PointData>\n";
  x += "      <CellData>\n" + section("CellData", "        ") + "      </CellData>\n";
  x += "      <Points>\n" + section("Points", "        ") + "      </Points>\n";
  x += "      <Cells>\n" + section("Cells", "        ") + "      </Cells>\n";
  x += "    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";
  return x;
}

// Arrays in the order their offsets were assigned by xmlHeader.
std::vector<const OutArray*> inOffsetOrder(const std::vector<OutArray>& arrays) {
  std::vector<const OutArray*> order;
  for (const char* parent : {"FieldData", "PointData", "CellData", "Points", "Cells"})
    for (const OutArray& a : arrays)
      if (a.parent == parent) order.push_back(&a);
  return order;
}

void writeArrays(std::FILE* f, const std::vector<OutArray>& arrays, bool compress) {
  std::vector<uint8_t> chunk;
  for (const OutArray* a : inOffsetOrder(arrays)) {
    if (compress) {
      std::fwrite(a->compressed.data(), 1, a->compressed.size(), f);
      continue;
    }
    uint64_t header = a->bytes;
    if constexpr (std::endian::native == std::endian::big) header = byteSwap(header);
    std::fwrite(&header, 8, 1, f);
    chunk.resize(std::min(a->bytes, kBlockSize));
    for (uint64_t b = 0; b < a->bytes; b += kBlockSize) {
      uint64_t n = std::min(kBlockSize, a->bytes - b);
      a->fill(b, n, chunk.data());
      std::fwrite(chunk.data(), 1, n, f);
    }
  }
}

}  // namespace

void writeVtu(const std::string& path, const mesh::UnstructuredMesh& m,
              const WriteOptions& options) {
  std::vector<OutArray> arrays = meshArrays(m);
  for (OutArray& a : arrays) {
    if (options.compress) {
      a.compressed = compressBlocks(a.bytes, kBlockSize, kZlibLevel, options.threads, a.fill);
      a.encodedSize = a.compressed.size();
    } else {
      a.encodedSize = 8 + a.bytes;
    }
  }
  const std::string header = xmlHeader(m, arrays, options.compress);
  writeFileAtomically(path, [&](const std::string& tmp) {
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw FileError(path, "cannot create: ", std::strerror(errno));
    std::fwrite(header.data(), 1, header.size(), f);
    writeArrays(f, arrays, options.compress);
    static const char kTail[] = "\n  </AppendedData>\n</VTKFile>\n";
    std::fwrite(kTail, 1, sizeof kTail - 1, f);
    bool ok = !std::ferror(f);
    ok = std::fclose(f) == 0 && ok;
    if (!ok) throw FileError(path, "write failed (disk full?)");
  });
}

}  // namespace sm::io
