// Element counts measured at a range of scales (gmsh 4.8, Debian 12, one thread; checked at 5 and
// 10 million: +0.5% and +2.3%). Between samples the scale is
// interpolated in log-log; finer than the last sample it follows the last segment's slope (about
// -2.9: tetrahedra go as scale^-3, the layer as scale^-2). Coarser than the first sample is not
// offered: no mesh coarser than that was checked, and the lander's legs and nozzles keep a minimum
// resolution whatever the scale.
#include "gen/size_calibration.h"

#include <cmath>
#include <span>

namespace sm::gen {
namespace {

struct Sample {
  double scale;
  double elements;
};

constexpr Sample kCapsule[] = {{5, 2485},     {4.2, 3427},    {3.5, 5283},    {2.9, 8235},
                               {2.4, 12871},  {2, 19815},     {1.65, 33467},  {1.35, 57550},
                               {1.1, 100931}, {0.9, 177414},  {0.74, 309166}, {0.6, 565414},
                               {0.5, 957098}, {0.42, 1591491}};
constexpr Sample kCapsuleHexBlock[] = {
    {5, 3286},      {4.2, 4399},   {3.5, 6644},    {2.9, 10566},   {2.4, 16869},
    {2, 25392},     {1.65, 43801}, {1.35, 75799},  {1.1, 128671},  {0.9, 224758},
    {0.74, 386366}, {0.6, 709263}, {0.5, 1193942}, {0.42, 1975371}};
constexpr Sample kLander[] = {{5, 10381},     {4.2, 11604},   {3.5, 13120},   {2.9, 16325},
                              {2.4, 20863},   {2, 28414},     {1.65, 42196},  {1.35, 68767},
                              {1.1, 117675},  {0.9, 201026},  {0.74, 346093}, {0.6, 615875},
                              {0.5, 1031186}, {0.42, 1696786}};
constexpr Sample kLanderHexBlock[] = {{5, 11145},     {4.2, 12701},   {3.5, 14987},   {2.9, 19295},
                                      {2.4, 25444},   {2, 35091},     {1.65, 53935},  {1.35, 89221},
                                      {1.1, 149307},  {0.9, 254507},  {0.74, 433558}, {0.6, 779608},
                                      {0.5, 1301694}, {0.42, 2129867}};

std::span<const Sample> samples(Body body, bool hexBlock) {
  if (body == Body::Lander) return hexBlock ? std::span(kLanderHexBlock) : std::span(kLander);
  return hexBlock ? std::span(kCapsuleHexBlock) : std::span(kCapsule);
}

}  // namespace

uint64_t cfdMinElements(Body body, bool hexBlock) {
  return uint64_t(samples(body, hexBlock).front().elements);
}

double cfdMeshScale(Body body, bool hexBlock, uint64_t targetElements) {
  const auto s = samples(body, hexBlock);
  const double target = std::log(double(targetElements));
  if (target <= std::log(s.front().elements)) return s.front().scale;
  // The segment holding the target, or the last one to extrapolate from.
  size_t i = 1;
  while (i + 1 < s.size() && std::log(s[i].elements) < target) ++i;
  const double n0 = std::log(s[i - 1].elements), n1 = std::log(s[i].elements);
  const double s0 = std::log(s[i - 1].scale), s1 = std::log(s[i].scale);
  return std::exp(s0 + (target - n0) * (s1 - s0) / (n1 - n0));
}

}  // namespace sm::gen
