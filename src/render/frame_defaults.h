// Defaults a user of ParaView or VisIt expects when they give no camera, step or range: the view
// frames the data, samples are half an element apart, and opacity 1 means an optical depth of
// about 8 across the data set.
#pragma once

#include "mesh/unstructured_mesh.h"
#include "prep/prepared_rank.h"

namespace sm::render {

// Sum over elements of volume^(1/3), and the element count: summed across ranks, their ratio is the
// mean element size (robust to the graded meshes CFD produces, unlike bounds / count).
struct ElementSizeSum {
  double sum = 0;
  uint64_t count = 0;
  double mean() const { return count ? sum / double(count) : 0.0; }
};
ElementSizeSum elementSizeSum(const mesh::UnstructuredMesh& mesh);

inline double defaultStep(double meanElementSize) {
  return 0.5 * meanElementSize;
}
inline double defaultUnitDistance(const mesh::Bounds& whole) {
  return whole.diagonal() / 8.0;
}

}  // namespace sm::render
