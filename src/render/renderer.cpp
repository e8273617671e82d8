#include "render/renderer.h"

#include <chrono>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "common/check.h"
#include "common/error.h"
#include "common/hash.h"
#include "compositor/device_util.h"
#include "render/frame_defaults.h"
#include "vk/vk_error.h"

namespace sm::render {
namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

glm::vec3 toFloat(const glm::dvec3& v) {
  return glm::vec3(v);
}

// Whether box b reaches within `pad` of the plane through `point` with unit normal `normal`.
bool boxMeetsPlane(const mesh::Bounds& b, const glm::dvec3& point, const glm::dvec3& normal,
                   double pad) {
  const glm::dvec3 c = b.center() - point, half = 0.5 * (b.hi - b.lo);
  return std::abs(glm::dot(c, normal)) <= glm::dot(half, glm::abs(normal)) + pad;
}

// The table the device reads. A constant range maps every value to the table's middle
// (scene::TransferFunction::lookup); the device gets that colour in every entry, so no rounding
// of the value (float, far from zero) can move a lookup off it.
// The transfer function in device lengths: extinction per device unit (prep::GlobalFrame::scale).
scene::TransferFunction deviceTransferFunction(const scene::TransferFunction& tf, double scale) {
  scene::TransferFunction d = tf;
  d.unitDistance *= scale;
  return d;
}

std::vector<glm::vec4> deviceTable(const scene::TransferFunction& tf) {
  if (tf.hi > tf.lo) return tf.table;
  return std::vector<glm::vec4>(tf.table.size(), glm::vec4(tf.lookup(tf.lo)));
}

}  // namespace

Renderer::Renderer(const vk::Context& ctx, const GpuScene& scene, comp::DeepCompositor& compositor,
                   std::shared_ptr<PassCache> passes, vk::Tracer tracer)
    : ctx_(ctx),
      scene_(scene),
      compositor_(compositor),
      passes_(passes && passes->serves(scene, compositor, tracer)
                  ? std::move(passes)
                  : std::make_shared<PassCache>(ctx, scene, compositor, tracer)),
      timestamps_(ctx, 8) {
  params_ = vk::Buffer(ctx, sizeof(gpu::FrameParams), vk::kStorageUsage, vk::MemoryUse::Upload,
                       "frame params");
  stats_ = vk::Buffer(ctx, sizeof(gpu::RenderStats), vk::kStorageUsage, vk::MemoryUse::Readback,
                      "render stats");
}

// The table depends on the transfer function only: rebuilt when that changes, not per frame.
void Renderer::updatePreintegration(const RenderSettings& s) {
  const scene::TransferFunction tf = deviceTransferFunction(s.transferFunction, scene_.scale());
  Hasher h;
  h.span(std::span<const glm::vec4>(tf.table))
      .pod(tf.lo)
      .pod(tf.hi)
      .pod(tf.scale)
      .pod(tf.opacityScale)
      .pod(tf.unitDistance);
  uint64_t key = h.digest();
  if (preintegration_.valid() && key == preintegrationKey_) return;
  preintegrationTable_ = buildPreintegration(tf);
  const PreintegrationTable& t = preintegrationTable_;
  const std::vector<uint64_t> words = t.deviceWords();
  const size_t bytes = words.size() * sizeof(uint64_t);
  if (!preintegration_.valid() || preintegration_.size() < bytes)
    preintegration_ = vk::Buffer(ctx_, bytes, vk::kStorageUsage, vk::MemoryUse::Device,
                                 "pre-integrated transfer function");
  preintegration_.upload(words.data(), bytes);
  preintegrationKey_ = key;
}

gpu::FrameParams Renderer::frameParams(const RenderSettings& s) const {
  if (s.width != compositor_.width() || s.height != compositor_.height())
    throw Error("image size ", s.width, "x", s.height, " differs from the compositor's ",
                compositor_.width(), "x", compositor_.height());
  const scene::TransferFunction& tf = s.transferFunction;
  if (tf.table.size() < 2) throw Error("transfer function has no table");
  scene::CameraFrame cam = scene::cameraFrame(s.camera, s.width, s.height);
  // Device lengths are world lengths times scene_.scale() (1 for data sets of ordinary size).
  const double scale = scene_.scale();
  const glm::dvec3 eye = scene_.toDevice(cam.eye);
  if (!useRays_) checkStep(s.dt * scale, eye, scene_.rebasedBounds());
  gpu::FrameParams p{};
  p.scene = scene_.refs();
  p.transferFunction = transferFunction_.valid() ? transferFunction_.address() : 0;
  p.stats = stats_.address();
  p.rays = useRays_ ? rays_.address() : 0;
  // Rays can only start inside the volume when the eye is within this rank's bounds (padded for
  // rounding); elsewhere the traversal skips the query that looks for such a start.
  const mesh::Bounds& b = scene_.rebasedBounds();
  const glm::dvec3 pad(1e-3 * b.diagonal() + 1e-30);
  bool inBounds = !b.empty && glm::all(glm::greaterThanEqual(eye, b.lo - pad)) &&
                  glm::all(glm::lessThanEqual(eye, b.hi + pad));
  // Parallel rays start anywhere on the plane through the eye: they may start inside when the
  // box reaches that plane.
  if (cam.parallel && !b.empty) inBounds = boxMeetsPlane(b, eye, cam.forward, pad.x);
  p.eyeMayBeInside = (useRays_ || inBounds) ? 1u : 0u;
  p.boundsValid = b.empty ? 0u : 1u;
  if (!b.empty) {
    p.boundsLo = glm::vec3(b.lo);
    p.boundsHi = glm::vec3(b.hi);
  }
  p.eye = toFloat(eye);
  p.forward = toFloat(cam.forward);
  p.right = toFloat(cam.right);
  p.upOrtho = toFloat(cam.upOrtho);
  // A parallel scale is a length: device lengths are world lengths times the scale.
  p.halfHeight = float(cam.parallel ? cam.halfHeight * scale : cam.halfHeight);
  p.parallel = cam.parallel ? 1u : 0u;
  p.aspect = float(cam.aspect);
  p.width = uint32_t(s.width);
  p.height = uint32_t(s.height);
  p.dt = float(s.dt * scale);
  if (tf.hi > tf.lo && tf.scale == scene::ScalarScale::Log) {  // the shader maps log2(s)
    p.tfLo = float(std::log2(tf.lo));
    p.tfScale = float(1.0 / std::log2(tf.hi / tf.lo));
  } else if (tf.hi > tf.lo) {
    p.tfLo = float(tf.lo);
    p.tfScale = float(1.0 / (tf.hi - tf.lo));
  } else {  // constant range: every entry of the device's table is the middle (deviceTable)
    p.tfLo = float(tf.lo);
    p.tfScale = 1.0f;
  }
  p.tfEntries = uint32_t(tf.table.size());
  p.sigmaScale = float(tf.opacityScale / (tf.unitDistance * scale));
  p.earlyTermination = float(s.earlyTermination);
  p.nanColor = glm::vec4(tf.nanColor, tf.nanOpacity);
  if (s.shading.enabled) {
    const Shading& sh = s.shading;
    if (!(sh.ambient >= 0 && sh.diffuse >= 0 && sh.specular >= 0 && sh.shininess >= 1 &&
          sh.shininess <= 1024))
      throw Error("--shading: coefficients must be >= 0 and the shininess in [1, 1024], not ",
                  sh.ambient, ",", sh.diffuse, ",", sh.specular, ",", sh.shininess);
    p.shadeAmbient = float(sh.ambient);
    p.shadeDiffuse = float(sh.diffuse);
    p.shadeSpecular = float(sh.specular);
    p.shadeShininess = float(sh.shininess);
  }
  setClipPlanes(s.clipPlanes, p);
  p.maxElementSteps = s.maxElementSteps;
  p.maxSegments = s.maxSegments;
  comp::DeviceLists lists = compositor_.lists();
  p.segCounts = lists.capacities;
  p.segOffsets = lists.offsets;
  p.fragCounts = lists.counts;
  p.fragments = lists.fragments;
  p.fragK = lists.fixedK;
  if (s.integration == Integration::ElementExact) {
    const PreintegrationTable& t = preintegrationTable_;
    p.preintegration = preintegration_.address();
    p.piScalarBins = uint32_t(t.scalarBins);
    p.piLengthBins = uint32_t(t.lengthBins);
    p.piSigmaMax = float(t.sigmaMax);
    p.piTauMax = float(t.tauMax);
    p.piCumulative = p.preintegration + t.deviceColorBytes();
    p.piCumulativeBins = uint32_t(t.cumulative.size());
    p.piLo = float(t.lo);
    p.piHi = float(t.hi);
  }
  return p;
}

void Renderer::setClipPlanes(std::span<const scene::ClipPlane> planes, gpu::FrameParams& p) const {
  static_assert(scene::kMaxClipPlanes == int(gpu::SM_MAX_CLIP_PLANES));
  scene::checkClipPlanes(planes, "clip planes");
  p.clipCount = uint32_t(planes.size());
  for (size_t i = 0; i < planes.size(); ++i) {
    // Device coordinates are rebased and uniformly scaled: the normal keeps its direction, the
    // offset is the rebased point's.
    const glm::dvec3 n = glm::normalize(planes[i].normal);
    const double w = -glm::dot(n, scene_.toDevice(planes[i].point));
    if (!(std::abs(w) < 1e30))
      throw Error("clip plane ", i + 1, ": its point is beyond the renderer's float range");
    p.clipPlanes[i] = glm::vec4(glm::vec3(n), float(w));
  }
}

void Renderer::writeParams(const gpu::FrameParams& p) {
  params_.upload(&p, sizeof p);
}

FrameResult Renderer::renderRays(const RenderSettings& settings,
                                 const std::vector<WorldRay>& rays) {
  std::vector<gpu::RayDesc> rebased(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    rebased[i] = {glm::vec3(scene_.toDevice(rays[i].origin)), glm::vec3(rays[i].direction)};
    // Each ray measures t from its own origin, in units of its direction's length.
    checkStep(settings.dt * scene_.scale() * glm::length(rays[i].direction),
              scene_.toDevice(rays[i].origin), scene_.rebasedBounds());
  }
  if (!rays_.valid() || rays_.size() < rebased.size() * sizeof(gpu::RayDesc))
    rays_ = vk::Buffer(ctx_, rebased.size() * sizeof(gpu::RayDesc), vk::kStorageUsage,
                       vk::MemoryUse::Device, "rays");
  rays_.upload(rebased.data(), rebased.size() * sizeof(gpu::RayDesc));
  RenderSettings s = settings;
  s.width = int(rebased.size());
  s.height = 1;
  useRays_ = true;
  FrameResult r = render(s);
  useRays_ = false;
  return r;
}

FrameResult Renderer::render(const RenderSettings& s, std::vector<glm::vec4> reuse) {
  auto t0 = std::chrono::steady_clock::now();
  scene::checkScale(s.transferFunction, "--log-scale");
  const std::vector<glm::vec4> table = deviceTable(s.transferFunction);
  if (!transferFunction_.valid() || transferFunction_.size() < table.size() * sizeof(glm::vec4))
    transferFunction_ = vk::Buffer(ctx_, table.size() * sizeof(glm::vec4), vk::kStorageUsage,
                                   vk::MemoryUse::Device, "transfer function");
  transferFunction_.upload(table.data(), table.size() * sizeof(glm::vec4));
  if (s.integration == Integration::ElementExact) updatePreintegration(s);
  passOptions_ =
      PassOptions{s.integration == Integration::ElementExact, s.shading.enabled, s.allTypePipelines,
                  !s.clipPlanes.empty(), s.transferFunction.scale == scene::ScalarScale::Log};
  gpu::FrameParams p = frameParams(s);
  FrameResult out;
  const gpu::RenderStats zero{};
  stats_.upload(&zero, sizeof zero);
  const uint32_t slots = twoPass() ? segmentCacheSlots(s) : 0;
  if (slots > 0 && ensureSegmentCache(uint64_t(s.width) * uint64_t(s.height) * slots *
                                      sizeof(gpu::CachedSegment)))
    renderCached(s, slots, p, out);
  else if (twoPass())
    renderTwoPass(s, p, out);
  else
    renderFixed(s, p, out);
  auto tc = std::chrono::steady_clock::now();
  out.pixels = std::move(reuse);
  compositor_.composite(s.compositeMethod, out.pixels);
  out.composite = compositor_.stats();
  out.timings.compositeMs = msSince(tc);
  stats_.download(&out.counters, sizeof out.counters);
  out.fragments = out.counters.fragments;
  out.timings.totalMs = msSince(t0);
  return out;
}

double Renderer::timedDispatch(const std::function<void(VkCommandBuffer)>& record) {
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    // A fence wait makes earlier submissions' writes visible to the host only: the scan's offsets
    // and the parameters rewritten since need this barrier to reach these shaders.
    comp::previousWorkBarrier(cmd);
    timestamps_.reset(cmd);
    timestamps_.write(cmd, 0);
    record(cmd);
    timestamps_.write(cmd, 1);
  });
  return timestamps_.ms(timestamps_.results(2), 0, 1);
}

void Renderer::scanCounts(gpu::FrameParams& p, FrameResult& out, bool segments) {
  auto t0 = std::chrono::steady_clock::now();
  out.segments = compositor_.prepareLists();
  lastSegmentTotal_ = out.segments;
  lastSegmentsKept_ = segments;
  out.timings.scanMs = msSince(t0);
  ensureSegments(p, segments ? out.segments : 0);
  if (!segments) p.segments = 0;  // the shaders write no segment where the address is 0
  writeParams(p);
}

void Renderer::renderTwoPass(const RenderSettings& s, gpu::FrameParams& p, FrameResult& out) {
  // Pass 1: count each pixel's segments (the compositor's list capacities).
  CountStorePass& traversal = passes_->traversal();
  writeParams(p);
  out.timings.traversalMs = timedDispatch([&](VkCommandBuffer cmd) {
    traversal.recordCount(cmd, params_.address(), s.width, s.height);
  });
  scanCounts(p, out, true);
  // Pass 2: store the segments at the scanned offsets, then march them into fragments.
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    comp::previousWorkBarrier(cmd);  // the scan's offsets (timedDispatch)
    timestamps_.reset(cmd);
    timestamps_.write(cmd, 0);
    traversal.recordStore(cmd, params_.address(), s.width, s.height);
    vk::computeBarrier(cmd);
    timestamps_.write(cmd, 1);
    passes_->march(passOptions_).record(cmd, params_.address(), s.width, s.height);
    timestamps_.write(cmd, 2);
  });
  auto ts = timestamps_.results(3);
  out.timings.traversalMs += timestamps_.ms(ts, 0, 1);
  out.timings.marchMs = timestamps_.ms(ts, 1, 2);
}

// The cache is an optimisation: it takes at most an eighth of the device (the lists and the scene
// need the rest), and where it cannot be had the stage-split passes render the same frame.
uint32_t Renderer::segmentCacheSlots(const RenderSettings& s) const {
  constexpr uint64_t kMaxSlots = 4;  // most rays of a rank have fewer segments
  const uint64_t slotBytes = uint64_t(s.width) * uint64_t(s.height) * sizeof(gpu::CachedSegment);
  const uint64_t budget = std::min(s.segmentCacheBytes, ctx_.deviceMemoryLimit() / 8);
  return uint32_t(std::min(kMaxSlots, budget / std::max<uint64_t>(slotBytes, 1)));
}

bool Renderer::ensureSegmentCache(uint64_t bytes) {
  if (segmentCache_.valid() && segmentCache_.size() >= bytes) return true;
  if (failedCacheBytes_ != 0 && bytes >= failedCacheBytes_) return false;  // tried: no room
  segmentCache_ = vk::Buffer();
  try {
    segmentCache_ =
        vk::Buffer(ctx_, bytes, vk::kStorageUsage, vk::MemoryUse::Device, "segment cache");
    return true;
  } catch (const vk::DeviceMemoryError&) {
    failedCacheBytes_ = bytes;
    return false;
  }
}

void Renderer::ensureSegments(gpu::FrameParams& p, uint64_t segments) {
  const uint64_t segBytes = std::max<uint64_t>(segments, 1) * sizeof(gpu::Segment);
  if (!segments_.valid() || segments_.size() < segBytes)
    segments_ = vk::Buffer(ctx_, segBytes + segBytes / 4, vk::kStorageUsage, vk::MemoryUse::Device,
                           "segments");
  p.segments = segments_.address();
  p.fragments = compositor_.lists().fragments;
}

void Renderer::renderCached(const RenderSettings& s, uint32_t slots, gpu::FrameParams& p,
                            FrameResult& out) {
  out.timings.fused = true;
  p.segCacheK = slots;
  p.segCache = segmentCache_.address();
  CountStorePass& pass = passes_->cached(passOptions_);
  // Pass 1: trace and march every ray, cache its first segments, count them.
  writeParams(p);
  out.timings.traversalMs = timedDispatch(
      [&](VkCommandBuffer cmd) { pass.recordCount(cmd, params_.address(), s.width, s.height); });
  scanCounts(p, out, s.keepSegments);
  // Pass 2: copy into the lists at the scanned offsets, and trace again the pixels the cache was
  // too short for, if any (the tracer's pipeline, run over every pixel, costs more than the copy).
  gpu::RenderStats counters;
  stats_.download(&counters, sizeof counters);
  StoreCachedPass& store = passes_->storeCached();
  out.timings.marchMs = timedDispatch([&](VkCommandBuffer cmd) {
    store.record(cmd, params_.address(), s.width, s.height);
    // Disjoint pixels: the two passes need no barrier between them.
    if (counters.cacheRetraces > 0) pass.recordStore(cmd, params_.address(), s.width, s.height);
  });
}

void Renderer::renderFixed(const RenderSettings& s, gpu::FrameParams& p, FrameResult& out) {
  writeParams(p);
  out.timings.traversalMs = timedDispatch([&](VkCommandBuffer cmd) {
    passes_->fused(passOptions_).record(cmd, params_.address(), s.width, s.height);
  });
  out.timings.fused = true;
}

std::vector<uint32_t> Renderer::lastSegmentCounts() const {
  if (!twoPass()) return {};
  std::vector<uint32_t> v(uint64_t(compositor_.width()) * compositor_.height());
  compositor_.downloadCapacities(v);
  return v;
}

std::vector<std::vector<gpu::Segment>> Renderer::lastSegments() const {
  std::vector<std::vector<gpu::Segment>> out;
  if (!twoPass() || !lastSegmentsKept_ || !segments_.valid()) return out;
  std::vector<uint32_t> counts = lastSegmentCounts();
  std::vector<gpu::Segment> all(lastSegmentTotal_);
  segments_.download(all.data(), all.size() * sizeof(gpu::Segment));
  out.resize(counts.size());
  uint64_t at = 0;
  for (size_t p = 0; p < counts.size(); ++p) {
    out[p].assign(all.begin() + at, all.begin() + at + counts[p]);
    at += counts[p];
  }
  return out;
}

std::vector<std::vector<comp::DcFragment>> Renderer::lastFragments() const {
  return compositor_.downloadLists();
}

std::vector<uint32_t> Renderer::lastFragmentCounts() const {
  std::vector<uint32_t> v(uint64_t(compositor_.width()) * compositor_.height());
  compositor_.downloadCounts(v);
  return v;
}

}  // namespace sm::render
