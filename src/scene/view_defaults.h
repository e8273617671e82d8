// Defaults a user of ParaView or VisIt expects when they give no camera, step or range: the view
// frames the data (scene/camera.h), samples are half an element apart (at least 256 across the
// data set), and opacity 1 means an optical depth of about 8 across the data set. Every front end
// (command line, viewer, in situ, benchmarks) takes them from here; the renderer only checks the
// step it is given (render/step_limits.h).
#pragma once

#include <algorithm>
#include <cstdint>

#include "mesh/bounds.h"
#include "mesh/unstructured_mesh.h"

namespace sm::scene {

// Sum over elements of volume^(1/3), and the element count: summed across ranks, their ratio is the
// mean element size (robust to the graded meshes CFD produces, unlike bounds / count).
struct ElementSizeSum {
  double sum = 0;
  uint64_t count = 0;
  double mean() const { return count ? sum / double(count) : 0.0; }
};
ElementSizeSum elementSizeSum(const mesh::UnstructuredMesh& mesh);

// Half an element: samples resolve each element's interpolant. The accuracy study (bench accuracy)
// refines meshes at this rule alone, and the benchmarks' cube scenes (bench features, counts) keep
// it so that their recorded figures stay comparable.
inline double elementStep(double meanElementSize) {
  return 0.5 * meanElementSize;
}

// A frame's step when none is given: half the mean element size, but never longer than the
// diagonal of the whole data set over kSamplesAcross. A coarse mesh (a few elements a side) would
// otherwise be sampled a dozen times across, and the grid t = k dt shows as nested rings (a 4^3
// hexahedral cube, 200x200 iso view: max error 0.36 against element-exact integration at half an
// element, 0.026 at the cap; HardCases.CoarseMeshesAreSampledAt256StepsAcrossByDefault). A mesh
// keeps half an element when that is shorter: a cube of more than about 75 hexahedra or 41
// six-tetrahedron cubes a side, the demo (560 samples across).
constexpr double kSamplesAcross = 256;
inline double defaultStep(double meanElementSize, const mesh::Bounds& whole) {
  const double step = elementStep(meanElementSize);
  return whole.empty ? step : std::min(step, whole.diagonal() / kSamplesAcross);
}
inline double defaultUnitDistance(const mesh::Bounds& whole) {
  return whole.diagonal() / 8.0;
}

}  // namespace sm::scene
