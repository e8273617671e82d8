// Host model of the compositor for tests: synthetic per-rank fragment lists, the device
// interface's list semantics (zero-opacity drop, fixed-K drop and merge, rgba8 quantisation), and
// the serial reference that sorts and blends the union of all ranks' fragments in double precision.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "compositor/deep_compositor.h"
#include "compositor/host_lists.h"

namespace sm::comp::test {

struct WorldSpec {
  int width = 17, height = 13, ranks = 2;
  uint32_t seed = 1;
  double emptyFraction = 0.2;  // pixels with no fragment on any rank
  uint32_t maxShort = 6;       // list length per rank of most pixels: 0..maxShort
  uint32_t maxLong = 100;      // ... and of a few pixels (longFraction): up to maxLong
  double longFraction = 0.05;
  double zeroOpacityFraction = 0.1;  // fragments with alpha 0 (and rgb != 0): must be dropped
  uint32_t depthSlots = 0;  // depths are multiples of 0.25 below depthSlots / 4 (0: 4 * longest),
                            // so that ranks often share a depth
};

// Every rank's raw lists, as a renderer submits them (before the device interface).
struct World {
  int width = 0, height = 0, ranks = 0;
  std::vector<HostLists> raw;  // per rank
  uint64_t pixels() const { return uint64_t(width) * uint64_t(height); }
};

World makeWorld(const WorldSpec& spec);
// Sets rank r's list at pixel p (replacing what was there).
void setList(World& w, int rank, uint64_t pixel, const std::vector<DcFragment>& list);

// One rank's lists after the device interface: zero-opacity fragments dropped, fixed-K overflow
// handled per mode (float32 arithmetic as in the shader), colours quantised for rgba8.
HostLists storedLists(const HostLists& raw, const CompositorOptions& o);
// Serial reference: union of all ranks' stored fragments per pixel, sorted by (depth, rank,
// index), blended front to back in double precision.
std::vector<glm::dvec4> deepReference(const World& w, const CompositorOptions& o);
// Single-fragment reference: each rank's stored list blended (float32, as the device does) into one
// fragment at its first depth, quantised for rgba8, then the ranks' fragments blended by depth.
std::vector<glm::dvec4> singleFragmentReference(const World& w, const CompositorOptions& o);

// Non-fatal gtest expectations: every channel within `tolerance`; reports the worst pixel.
void expectImageNear(const std::vector<glm::vec4>& got, const std::vector<glm::dvec4>& want,
                     double tolerance, const std::string& label);
// The largest per-pixel L2 difference.
double maxDifference(const std::vector<glm::vec4>& a, const std::vector<glm::dvec4>& b);

}  // namespace sm::comp::test
