// The clip span along a ray (scene/clip_plane.h): the interval that every plane keeps.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/error.h"
#include "scene/clip_plane.h"

namespace sm::scene {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(ClipSpan, NoPlaneKeepsTheWholeRay) {
  ClipSpan s = clipSpan({}, {0, 0, 0}, {1, 0, 0});
  EXPECT_EQ(s.lo, -kInf);
  EXPECT_EQ(s.hi, kInf);
  EXPECT_FALSE(s.empty());
}

TEST(ClipSpan, APlaneFacingAlongTheRayKeepsWhatLiesBeyondIt) {
  // x >= 2 along x from the origin at speed 4 (t in units of |dir|): from t = 0.5 on.
  const ClipPlane p{{2, 0, 0}, {3, 0, 0}};
  ClipSpan s = clipSpan(std::span(&p, 1), {0, 5, 5}, {4, 0, 0});
  EXPECT_DOUBLE_EQ(s.lo, 0.5);
  EXPECT_EQ(s.hi, kInf);
  // The same plane against the ray keeps what lies before it.
  s = clipSpan(std::span(&p, 1), {6, 0, 0}, {-1, 0, 0});
  EXPECT_EQ(s.lo, -kInf);
  EXPECT_DOUBLE_EQ(s.hi, 4.0);
}

TEST(ClipSpan, ObliquePlanesIntersect) {
  // Keep x + y >= 1 and x <= 3 along the ray (0, 0, 0) + t (1, 1, 0): t in [0.5, 3).
  const ClipPlane planes[] = {{{0.5, 0.5, 7}, {1, 1, 0}}, {{3, -2, 0}, {-2, 0, 0}}};
  ClipSpan s = clipSpan(planes, {0, 0, 0}, {1, 1, 0});
  EXPECT_DOUBLE_EQ(s.lo, 0.5);
  EXPECT_DOUBLE_EQ(s.hi, 3.0);
}

TEST(ClipSpan, PlanesThatKeepNothingTogetherGiveAnEmptySpan) {
  const ClipPlane planes[] = {{{2, 0, 0}, {1, 0, 0}}, {{1, 0, 0}, {-1, 0, 0}}};  // x >= 2, x <= 1
  EXPECT_TRUE(clipSpan(planes, {0, 0, 0}, {1, 0.1, 0}).empty());
}

TEST(ClipSpan, ARayParallelToAPlaneIsKeptByItsSide) {
  const ClipPlane p{{0, 1, 0}, {0, 1, 0}};  // y >= 1
  EXPECT_FALSE(clipSpan(std::span(&p, 1), {0, 2, 0}, {1, 0, 0}).empty());
  EXPECT_FALSE(clipSpan(std::span(&p, 1), {0, 1, 0}, {1, 0, 0}).empty());  // on it: kept
  ClipSpan s = clipSpan(std::span(&p, 1), {0, 0.5, 0}, {1, 0, 0});
  EXPECT_TRUE(s.empty());
}

TEST(ClipPlanes, ImpossiblePlanesAreRefusedByNumber) {
  auto message = [](std::vector<ClipPlane> planes) {
    try {
      checkClipPlanes(planes);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message(std::vector<ClipPlane>(6)), "accepted");
  EXPECT_EQ(message(std::vector<ClipPlane>(7)), "--clip: 7 clip planes, at most 6");
  EXPECT_EQ(message({{}, {{0, 0, 0}, {0, 0, 1e-200}}}), "--clip: clip plane 2 has a zero normal");
  EXPECT_EQ(message({{{0, 0, 0}, {0, kInf, 0}}}),
            "--clip: clip plane 1 has a non-finite point or normal");
  EXPECT_EQ(message({{{NAN, 0, 0}, {0, 0, 1}}}),
            "--clip: clip plane 1 has a non-finite point or normal");
}

}  // namespace
}  // namespace sm::scene
