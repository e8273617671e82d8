// Whether a later step of a time series holds step 0's points. A series is rendered on the mesh
// of its first file (prepared, shelled and uploaded once), so a step whose points moved (a moving
// or deforming mesh, or one renumbered between steps with the same counts) would draw its values
// at step 0's positions: a wrong image with no error. Counts alone (checked from the headers when
// the series is listed) do not catch that; the points themselves, read when a step's values are
// read, do.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "io/mesh_io.h"
#include "io/series.h"

namespace sm::io {

// The points a step file holds, in file order: every piece of a .vtu, the pieces `options` choose
// of a .pvtu (in order), or the whole file read as readMesh reads it.
struct StepPoints {
  std::vector<glm::dvec3> points;
  // (file, points) per piece read, for naming a point in a message.
  std::vector<std::pair<std::string, uint64_t>> pieces;
};
StepPoints readStepPoints(const std::string& file, const ReadOptions& options);

// The first index at which the two differ as positions (-0 and +0 alike), or none.
std::optional<uint64_t> firstMovedPoint(const std::vector<glm::dvec3>& first,
                                        const std::vector<glm::dvec3>& later);

// Throws sm::FileError naming `path`, step k's file, the first point that moved and both
// positions when step k's points are not step 0's. Step 0's points are hashed once per process
// while its files are unchanged, so a stream of steps reads each later step's points only.
void checkSamePoints(const std::string& path, const std::vector<SeriesStep>& steps, uint64_t k,
                     const ReadOptions& options);

// The message checkSamePoints throws with, for steps compared in memory (formats read whole).
[[noreturn]] void throwMovedPoint(const std::string& path, uint64_t k, const SeriesStep& step,
                                  const std::string& where, const glm::dvec3& first,
                                  const glm::dvec3& later);

}  // namespace sm::io
