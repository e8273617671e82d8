#include "prep/prepare.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include <glm/common.hpp>

#include "common/check.h"
#include "common/error.h"
#include "common/timer.h"
#include "prep/compaction.h"
#include "prep/shell.h"
#include "prep/vertex_order.h"

namespace sm::prep {
namespace {

// Rebased float positions in the global order; returns order (new -> old).
std::vector<uint32_t> orderAndRebase(mesh::UnstructuredMesh& mesh, const GlobalFrame& frame,
                                     std::vector<float>& positions) {
  std::vector<uint32_t> order = globalVertexOrder(mesh.points, frame);
  positions.resize(3 * order.size());
  std::vector<uint8_t> used;  // built when a point out of float range is met
  for (size_t i = 0; i < order.size(); ++i) {
    glm::dvec3 p = (mesh.points[order[i]] - frame.origin) * frame.scale;
    // Readers accept any finite double; the device works in float around the frame's origin. A
    // point no element uses is never drawn (the frame leaves it out): it is kept, clamped.
    if (!(std::abs(p.x) <= FLT_MAX && std::abs(p.y) <= FLT_MAX && std::abs(p.z) <= FLT_MAX)) {
      if (used.empty()) used = mesh::usedPoints(mesh);
      if (used[order[i]])
        throw Error(mesh.source, ": point ", order[i], " is too far from the mesh's centre for ",
                    "single precision (coordinates must stay within 3.4e38 of it)");
      p = glm::clamp(p, glm::dvec3(-FLT_MAX), glm::dvec3(FLT_MAX));
    }
    positions[3 * i] = float(p.x);
    positions[3 * i + 1] = float(p.y);
    positions[3 * i + 2] = float(p.z);
  }
  std::vector<glm::dvec3>().swap(mesh.points);
  return order;
}

void remapElements(ElementArrays& elements, const std::vector<uint32_t>& order) {
  std::vector<uint32_t> newId(order.size());
  for (size_t i = 0; i < order.size(); ++i) newId[order[i]] = uint32_t(i);
  for (auto& cells : elements)
    for (uint32_t& v : cells) v = newId[v];
}

}  // namespace

uint64_t PreparedRank::numElements() const {
  uint64_t n = 0;
  for (uint64_t c : elementCount) n += c;
  return n;
}

uint32_t PreparedRank::typesPresent() const {
  uint32_t bits = 0;
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t)
    if (elementCount[t]) bits |= 1u << t;
  return bits;
}

// Every element index the word bound admits is also one an element reference (index << 2 | type)
// holds without reaching SM_NO_NEIGHBOR (~0u, index 2^30 - 1 of type 3): smElemRef cannot wrap
// for any scene that passed checkShaderIndexRange, in either encoding.
static_assert([] {
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t)
    for (bool compact : {false, true})
      if (maxElementsOnRank(t, compact) >= gpu::SM_MAX_ELEMS_PER_TYPE - 1) return false;
  return true;
}());

void checkShaderIndexRange(const std::string& source, const SceneSizes& sizes, bool compact) {
  // Compared by count, not by count x words, which could wrap for absurd counts.
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t)
    if (sizes.elements[t] > maxElementsOnRank(t, compact))
      throw Error(source, ": ", sizes.elements[t], " ", mesh::cellTypePluralName(mesh::CellType(t)),
                  " on one rank; the shaders' 32-bit indices reach at most ",
                  maxElementsOnRank(t, compact), " (use more ranks)");
  if (sizes.vertices > kMaxVerticesOnRank)
    throw Error(source, ": ", sizes.vertices, " vertices on one rank; the shaders' 32-bit indices",
                " reach at most ", kMaxVerticesOnRank, " (use more ranks)");
  if (sizes.shellTriangles > kMaxShellTrianglesOnRank)
    throw Error(source, ": a shell of ", sizes.shellTriangles, " triangles on one rank; the",
                " shaders' 32-bit indices reach at most ", kMaxShellTrianglesOnRank,
                " (use more ranks, or clusters with less surface)");
}

PrepResult prepareRank(mesh::UnstructuredMesh& mesh, const GlobalFrame& frame,
                       const PrepOptions& options) {
  PrepResult result;
  PreparedRank& r = result.rank;
  r.frame = frame;
  r.compact = options.compact;
  // Before any work; the bound also keeps every element reference below 2^30 (static_assert).
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t)
    r.elementCount[t] = mesh.cells[t].size() / gpu::SM_NUM_VERTS[t];
  SceneSizes sizes;
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t) sizes.elements[t] = r.elementCount[t];
  sizes.vertices = mesh.points.size();
  checkShaderIndexRange(mesh.source, sizes, options.compact);

  Timer timer;
  r.vertexSource = orderAndRebase(mesh, frame, r.positions);
  ElementArrays elements;
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t) {
    elements[t] = std::move(mesh.cells[t]);
    // Cluster ids describe the cells just taken (and partitioning is over): 4 bytes per element
    // that would otherwise stay resident through connectivity, preparation's peak.
    std::vector<int32_t>().swap(mesh.clusters[t]);
  }
  remapElements(elements, r.vertexSource);
  orderElementsByVertex(elements, uint32_t(r.numVertices()));
  result.timings.vertexOrder = timer.seconds();

  timer.reset();
  result.connectivity =
      computeConnectivity(elements, r.numVertices(), r.neighbors, mesh.source, [&](uint32_t v) {
        // The input's points are freed by now; float positions suffice here.
        return frame.origin + glm::dvec3(r.positions[3 * uint64_t(v)],
                                         r.positions[3 * uint64_t(v) + 1],
                                         r.positions[3 * uint64_t(v) + 2]) /
                                  frame.scale;
      });
  result.timings.connectivity = timer.seconds();

  timer.reset();
  // Each shell face becomes one or two triangles: too many faces are refused before the triangles
  // are made, which also keeps their count, and the sort's 32-bit triangle numbers, below 2^32.
  sizes.shellTriangles = result.connectivity.boundaryFaces;
  checkShaderIndexRange(mesh.source, sizes, options.compact);
  Shell shell = extractShell(elements, r.neighbors, r.positions);
  sizes.shellTriangles = shell.refs.size();
  checkShaderIndexRange(mesh.source, sizes, options.compact);
  r.shellAdjacency = shellAdjacency(shell.indices);
  r.shellIndices = std::move(shell.indices);
  r.shellRefs = std::move(shell.refs);
  if (options.compact) r.shellOther = std::move(shell.other);
  result.timings.shell = timer.seconds();

  timer.reset();
  for (uint32_t t = 0; t < mesh::kNumCellTypes; ++t) {
    if (options.compact && t != gpu::SM_HEX) {
      r.elements[t] = compactElements(t, elements[t]);
      std::vector<uint32_t>().swap(elements[t]);
    } else {
      r.elements[t] = std::move(elements[t]);
    }
  }
  result.timings.compaction = timer.seconds();
  return result;
}

std::vector<float> gatherScalars(const PreparedRank& rank, std::span<const float> meshValues) {
  std::vector<float> out(rank.vertexSource.size());
  for (size_t i = 0; i < out.size(); ++i) {
    uint32_t src = rank.vertexSource[i];
    SM_CHECK_LT(src, meshValues.size());
    out[i] = meshValues[src];
  }
  return out;
}

}  // namespace sm::prep
