#include "bench/reference_images.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "common/error.h"
#include "common/file_util.h"
#include "common/hash.h"
#include "common/timer.h"

namespace sm::app::bench {
namespace {

constexpr char kMagic[8] = {'S', 'M', 'R', 'E', 'F', 'I', 'M', '1'};

uint64_t imageKey(const mesh::UnstructuredMesh& m, std::span<const float> values,
                  const scene::Camera& c, int w, int h, const scene::TransferFunction& tf,
                  const ref::RenderSettings& s) {
  Hasher k;
  k.str("reference image v1");
  k.span(std::span<const glm::dvec3>(m.points));
  for (const auto& cells : m.cells) k.span(std::span<const uint32_t>(cells));
  k.span(values);
  k.pod(c.eye).pod(c.at).pod(c.up).pod(c.fovyDeg).pod(w).pod(h);
  k.span(std::span<const glm::vec4>(tf.table));
  k.pod(tf.lo).pod(tf.hi).pod(tf.opacityScale).pod(tf.unitDistance);
  k.pod(s.dt).pod(int(s.mode)).pod(s.earlyTermination).pod(s.tolerance);
  return k.digest();
}

bool readCached(const std::string& path, int w, int h, scene::Image& out) {
  if (!fileExists(path)) return false;
  std::vector<uint8_t> bytes = readFile(path);
  const size_t want = sizeof kMagic + 2 * sizeof(int32_t) + size_t(w) * h * sizeof(glm::vec4);
  if (bytes.size() != want || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) return false;
  int32_t dims[2];
  std::memcpy(dims, bytes.data() + sizeof kMagic, sizeof dims);
  if (dims[0] != w || dims[1] != h) return false;
  out = scene::Image(w, h);
  std::memcpy(out.pixels.data(), bytes.data() + sizeof kMagic + sizeof dims,
              out.pixels.size() * sizeof(glm::vec4));
  return true;
}

void writeCached(const std::string& path, const scene::Image& img) {
  std::vector<uint8_t> bytes(sizeof kMagic + 2 * sizeof(int32_t));
  std::memcpy(bytes.data(), kMagic, sizeof kMagic);
  int32_t dims[2] = {img.width, img.height};
  std::memcpy(bytes.data() + sizeof kMagic, dims, sizeof dims);
  const auto* px = reinterpret_cast<const uint8_t*>(img.pixels.data());
  bytes.insert(bytes.end(), px, px + img.pixels.size() * sizeof(glm::vec4));
  writeBytesAtomically(path, bytes);
}

}  // namespace

ReferenceImage referenceImage(const ref::ReferenceRenderer& renderer, std::span<const float> values,
                              const scene::Camera& camera, int w, int h,
                              const scene::TransferFunction& tf, const ref::RenderSettings& s,
                              const std::string& cacheDir) {
  char name[40];
  std::snprintf(name, sizeof name, "%016llx.smref",
                (unsigned long long)imageKey(renderer.mesh(), values, camera, w, h, tf, s));
  ReferenceImage r;
  r.path = joinPath(cacheDir, name);
  if (readCached(r.path, w, h, r.image)) {
    r.cached = true;
    return r;
  }
  std::fprintf(stderr, "rendering the CPU reference (%s, %dx%d); kept in %s\n",
               s.mode == ref::RenderMode::Grid ? "grid" : "converged", w, h, r.path.c_str());
  Timer t;
  r.image = renderer.render(camera, w, h, values, tf, s).image;
  r.seconds = t.seconds();
  std::filesystem::create_directories(cacheDir);
  writeCached(r.path, r.image);
  return r;
}

scene::Image quantised8(const scene::Image& image) {
  scene::Image q = image;
  for (glm::vec4& p : q.pixels)
    for (int c = 0; c < 4; ++c) p[c] = std::round(std::clamp(p[c], 0.0f, 1.0f) * 255.0f) / 255.0f;
  return q;
}

}  // namespace sm::app::bench
