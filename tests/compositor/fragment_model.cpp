#include "fragment_model.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>

#include <gtest/gtest.h>

namespace sm::comp::test {
namespace {

struct Keyed {
  double depth;
  int rank;
  uint32_t index;
  glm::dvec4 color;
};

// Moves c away from the half-way points of 8-bit quantisation, where the device's rounding of
// packUnorm4x8 is implementation-defined (and float evaluation order decides), so that the model
// quantises every submitted fragment exactly as the device does.
float awayFromHalfSteps(float c) {
  float steps = c * 255.0f;
  float frac = steps - std::floor(steps);
  return std::abs(frac - 0.5f) < 0.05f ? (std::floor(steps) + 0.3f) / 255.0f : c;
}

DcFragment randomFragment(std::mt19937& rng, float depth, bool zeroOpacity) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  float a = zeroOpacity ? 0.0f : awayFromHalfSteps(0.02f + 0.6f * u(rng));
  // Premultiplied colour; a zero-opacity fragment keeps a colour so that storing it would show.
  float scale = zeroOpacity ? 0.5f : a;
  auto channel = [&] { return awayFromHalfSteps(scale * u(rng)); };
  float r = channel(), g = channel(), b = channel();
  return {glm::vec4(r, g, b, a), depth};
}

float quantise(float c) {
  return std::round(std::clamp(c, 0.0f, 1.0f) * 255.0f) / 255.0f;
}

DcFragment over(const DcFragment& front, const DcFragment& back) {
  return {front.color + (1.0f - front.color.a) * back.color, front.depth};
}

DcFragment encodeDecode(DcFragment f, Encoding e) {
  if (e == Encoding::Rgba8)
    f.color = {quantise(f.color.r), quantise(f.color.g), quantise(f.color.b), quantise(f.color.a)};
  return f;
}

// dcMergeInto of fragment_list.glsl on a full list of stored (encoded) fragments; `f` is the raw
// fragment the renderer submitted.
void mergeInto(std::vector<DcFragment>& list, const DcFragment& f, Encoding e) {
  const size_t n = list.size();
  size_t lowest = n;
  float lowestA = f.color.a;
  for (size_t i = 0; i < n; ++i)
    if (list[i].color.a < lowestA) {
      lowestA = list[i].color.a;
      lowest = i;
    }
  size_t front = lowest == 0 ? 0 : lowest - 1, back = front + 1;
  list[front] = encodeDecode(over(list[front], back == n ? f : list[back]), e);
  if (back == n) return;
  list.erase(list.begin() + long(back));
  list.push_back(encodeDecode(f, e));
}

std::vector<DcFragment> storeList(const DcFragment* raw, uint32_t n, const CompositorOptions& o) {
  std::vector<DcFragment> out;
  const bool fixed = o.mode != ListMode::TwoPass;
  for (uint32_t i = 0; i < n; ++i) {
    if (!(raw[i].color.a > 0.0f)) continue;
    if (!fixed || out.size() < o.fixedK)
      out.push_back(encodeDecode(raw[i], o.encoding));
    else if (o.mode == ListMode::FixedMerge)
      mergeInto(out, raw[i], o.encoding);
  }
  return out;
}

// Per pixel, every rank's stored fragments (or the given per-rank flattening of them).
template <typename PerRank>
std::vector<glm::dvec4> blendByDepth(const World& w, const CompositorOptions& o, PerRank perRank) {
  std::vector<HostLists> stored;
  for (const HostLists& r : w.raw) stored.push_back(storedLists(r, o));
  std::vector<uint64_t> at(stored.size(), 0);
  std::vector<glm::dvec4> image(w.pixels());
  for (uint64_t p = 0; p < w.pixels(); ++p) {
    std::vector<Keyed> all;
    for (size_t r = 0; r < stored.size(); ++r) {
      const uint32_t n = stored[r].counts[p];
      perRank(int(r), stored[r].fragments.data() + at[r], n, all);  // may be empty
      at[r] += n;
    }
    std::sort(all.begin(), all.end(), [](const Keyed& a, const Keyed& b) {
      return std::tie(a.depth, a.rank, a.index) < std::tie(b.depth, b.rank, b.index);
    });
    glm::dvec4 acc(0.0);
    for (const Keyed& k : all) acc += (1.0 - acc.a) * k.color;
    image[p] = acc;
  }
  return image;
}

}  // namespace

World makeWorld(const WorldSpec& s) {
  std::mt19937 rng(s.seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  World w{s.width, s.height, s.ranks, std::vector<HostLists>(size_t(s.ranks))};
  const uint32_t slots = s.depthSlots ? s.depthSlots : 4 * std::max(s.maxLong, s.maxShort) + 4;
  for (uint64_t p = 0; p < w.pixels(); ++p) {
    const bool empty = u(rng) < s.emptyFraction;
    const uint32_t most = u(rng) < s.longFraction ? s.maxLong : s.maxShort;
    for (int r = 0; r < s.ranks; ++r) {
      HostLists& l = w.raw[size_t(r)];
      uint32_t n = empty ? 0 : uint32_t(rng() % (most + 1));
      n = std::min(n, slots);
      // Distinct depth slots per rank (a ray's segments on one rank never overlap); other ranks
      // draw from the same slots, so equal depths across ranks are common.
      std::vector<uint32_t> depth(slots);
      for (uint32_t i = 0; i < slots; ++i) depth[i] = i;
      std::shuffle(depth.begin(), depth.end(), rng);
      depth.resize(n);
      std::sort(depth.begin(), depth.end());
      for (uint32_t d : depth)
        l.fragments.push_back(
            randomFragment(rng, 0.25f * float(d), u(rng) < s.zeroOpacityFraction));
      l.counts.push_back(n);
    }
  }
  return w;
}

void setList(World& w, int rank, uint64_t pixel, const std::vector<DcFragment>& list) {
  HostLists& l = w.raw[size_t(rank)];
  uint64_t at = 0;
  for (uint64_t p = 0; p < pixel; ++p) at += l.counts[p];
  auto first = l.fragments.begin() + long(at);
  l.fragments.erase(first, first + l.counts[pixel]);
  l.fragments.insert(l.fragments.begin() + long(at), list.begin(), list.end());
  l.counts[pixel] = uint32_t(list.size());
}

HostLists storedLists(const HostLists& raw, const CompositorOptions& o) {
  HostLists out;
  uint64_t at = 0;
  for (uint32_t n : raw.counts) {
    std::vector<DcFragment> l = storeList(raw.fragments.data() + at, n, o);  // may be empty
    at += n;
    out.counts.push_back(uint32_t(l.size()));
    out.fragments.insert(out.fragments.end(), l.begin(), l.end());
  }
  return out;
}

std::vector<glm::dvec4> deepReference(const World& w, const CompositorOptions& o) {
  return blendByDepth(w, o, [](int r, const DcFragment* f, uint32_t n, std::vector<Keyed>& all) {
    for (uint32_t i = 0; i < n; ++i) all.push_back({f[i].depth, r, i, glm::dvec4(f[i].color)});
  });
}

std::vector<glm::dvec4> singleFragmentReference(const World& w, const CompositorOptions& o) {
  return blendByDepth(w, o, [&](int r, const DcFragment* f, uint32_t n, std::vector<Keyed>& all) {
    if (n == 0) return;
    DcFragment acc{glm::vec4(0.0f), f[0].depth};
    for (uint32_t i = 0; i < n; ++i) acc = over(acc, f[i]);
    acc = encodeDecode(acc, o.encoding);
    all.push_back({acc.depth, r, 0, glm::dvec4(acc.color)});
  });
}

double maxDifference(const std::vector<glm::vec4>& a, const std::vector<glm::dvec4>& b) {
  double worst = 0.0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(double(a[i][c]) - b[i][c]));
  return worst;
}

void expectImageNear(const std::vector<glm::vec4>& got, const std::vector<glm::dvec4>& want,
                     double tolerance, const std::string& label) {
  EXPECT_EQ(got.size(), want.size()) << label;
  if (got.size() != want.size()) return;
  size_t bad = 0, worstPixel = 0;
  double worst = 0.0;
  for (size_t i = 0; i < got.size(); ++i) {
    for (int c = 0; c < 4; ++c) {
      double e = std::abs(double(got[i][c]) - want[i][c]);
      if (!(e <= tolerance)) ++bad;
      if (!(e <= worst)) {
        worst = e;
        worstPixel = i;
      }
    }
  }
  EXPECT_EQ(bad, 0u) << label << ": " << bad << " channels off by more than " << tolerance
                     << "; worst " << worst << " at pixel " << worstPixel << " (got "
                     << got[worstPixel].r << " " << got[worstPixel].g << " " << got[worstPixel].b
                     << " " << got[worstPixel].a << ", want " << want[worstPixel].r << " "
                     << want[worstPixel].g << " " << want[worstPixel].b << " " << want[worstPixel].a
                     << ")";
}

}  // namespace sm::comp::test
