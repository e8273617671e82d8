// Structs the renderer's shaders and C++ share (scalar block layout). In C++ they live in
// sm::gpu, with static_asserts on sizes; every 64-bit member comes first so that C++'s natural
// layout equals GLSL's scalar layout.
#ifndef SM_RENDER_TYPES_H
#define SM_RENDER_TYPES_H

#include "glsl_cpp.h"

#ifdef __cplusplus
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
namespace sm::gpu {
using vec3 = glm::vec3;
using vec4 = glm::vec4;
#endif

// Clip planes a frame can carry (scene::kMaxClipPlanes, checked where they are written).
SM_CONST uint SM_MAX_CLIP_PLANES = 6u;

// Where one rank's prepared data lives on the device (buffer device addresses).
struct SceneRefs {
  uint64_t vertices;        // vec4 per vertex: xyz rebased, w the current field and step's scalar
  uint64_t elements[4];     // per type: XOR-compacted or plain records
  uint64_t neighbors[4];    // per type: one element reference per face slot
  uint64_t shellIndices;    // 3 vertex ids per shell triangle
  uint64_t shellRefs;       // element behind each shell triangle
  uint64_t shellOther;      // compact mode: 4th vertex of the quad a triangle came from, or ~0u
  uint64_t shellAdjacency;  // 3 per triangle: the shell triangle across each edge, or ~0u
};

// Per-frame parameters of one rank.
struct FrameParams {
  SceneRefs scene;
  uint64_t transferFunction;  // vec4 (rgb, opacity) entries
  uint64_t segCounts;         // uint per pixel: segments found by traversal (two-pass count)
  uint64_t segOffsets;        // uint per pixel: exclusive prefix sum of segCounts
  uint64_t segments;          // Segment per segment
  uint64_t fragCounts;        // uint per pixel: fragments written
  uint64_t fragments;         // fragment storage (encoding per the compositor)
  uint64_t stats;             // RenderStats
  uint64_t rays;              // 0: camera rays; else one RayDesc per "pixel" (width x 1 image)
  uint64_t preintegration;    // element-exact mode: PreintegrationTable::deviceWords(): colours,
  uint64_t piCumulative;      // ... cumulative extinction pairs (then the two ends' rgb, sigma)
  uint64_t segCache;          // cached two-pass: CachedSegment per slot, segCacheK slots per pixel
  // Camera, rebased to the scene origin (scene::CameraFrame): halfHeight is tan(fovy / 2), or with
  // `parallel` the parallel scale in device units, the rays then starting on the plane through
  // the eye.
  vec3 eye;
  float halfHeight;
  vec3 forward;
  float aspect;
  vec3 right;
  uint width;
  vec3 upOrtho;
  uint height;
  // This rank's bounding box (rebased): a segment that ends on it ends the ray's traversal.
  vec3 boundsLo;
  uint segCacheK;  // cached two-pass: slots per pixel (0: the stage-split passes are in use)
  vec3 boundsHi;
  uint boundsValid;
  // Sampling and transfer function.
  float dt;
  float tfLo;
  float tfScale;  // 1 / (hi - lo); on a log scale tfLo = log2(lo), tfScale = 1 / log2(hi / lo)
  uint tfEntries;
  float sigmaScale;        // opacityScale / unitDistance
  float earlyTermination;  // stop once accumulated opacity reaches this
  uint maxElementSteps;    // per segment: the march's step bound
  uint maxSegments;        // per ray: the traversal's bound
  uint fragK;              // fixed-length lists: slots per pixel
  uint eyeMayBeInside;     // 0 when the eye is outside this rank's bounds: no ray starts inside
  uint piScalarBins;       // pre-integration table size along front and back scalar
  uint piLengthBins;       // ... and along sqrt(optical depth / piTauMax)
  float piSigmaMax;        // extinction that maps a length to optical depth for the table
  float piTauMax;
  uint piCumulativeBins;
  float piLo;  // scalar range of the pre-integration tables
  float piHi;
  uint parallel;       // 1: parallel projection (camera above)
  float shadeAmbient;  // Blinn-Phong coefficients (src/render/render_settings.h, Shading)
  float shadeDiffuse;
  float shadeSpecular;
  float shadeShininess;
  // Clip planes (pipelines specialised with kClip only): each keeps dot(xyz, x) + w >= 0 for x
  // rebased, xyz a unit normal; a ray samples only the t that every plane keeps.
  uint clipCount;
  uint pad1, pad2, pad3;
  vec4 clipPlanes[SM_MAX_CLIP_PLANES];
  // NaN and infinite data: rgb and opacity (scene::TransferFunction::nanColor; 0: transparent).
  vec4 nanColor;
};

// An explicit ray (rebased origin, unit direction), for tests that aim rays at vertices and edges.
struct RayDesc {
  vec3 origin;
  vec3 direction;
};

// One segment of a ray inside this rank's volume, from shell traversal.
struct Segment {
  float tEntry;  // distance of the entry crossing (0 for a segment that starts inside)
  float reserved;
  uint entryTriangle;  // shell triangle the ray enters through, or ~0u: the segment starts inside
                       // the volume (the camera is in it) and is found from exitTriangle
  uint exitTriangle;   // only for segments that start inside: the first exit
};

// Cached two-pass lists: what the first (counting) pass found and integrated for one segment, so
// that the second pass copies it instead of traversing and marching again.
struct CachedSegment {
  Segment segment;
  vec4 color;   // the segment's fragment: premultiplied rgba ...
  float depth;  // ... and entry distance
  uint hasFragment;
};

// Global counters (atomics) for --stats.
struct RenderStats {
  uint lostRays;       // marches that lost their element (must be zero on hard cases)
  uint grazingSkips;   // hardware entries the exact predicate says the ray only grazes
  uint entryWalks;     // entries corrected by walking the shell adjacency
  uint stepLimitHits;  // marches stopped by maxElementSteps
  uint segments;
  uint fragments;
  uint overflow;       // fragments dropped or merged by fixed-length lists
  uint elementSteps;   // elements visited: low 32 bits (elementStepCount)
  uint samples;        // samples taken: low 32 bits (sampleCount)
  uint cameraInside;   // rays whose first segment starts at the camera
  uint boxExits;       // rays whose traversal ended where a segment left the rank's bounding box
  uint shellQueries;   // acceleration-structure queries (a probe that finds nothing is one more)
  uint cacheRetraces;  // cached two-pass lists: pixels with more segments than cache slots,
                       // traced again in the store pass
  // High words of elementSteps and samples, which pass 2^32 on large images (a 4096² demo frame
  // at the default step takes 2.6 G samples): carried by the add that wraps the low word, so that
  // no 64-bit atomics are needed.
  uint elementStepsHigh;
  uint samplesHigh;
};

#ifdef __cplusplus
static_assert(sizeof(SceneRefs) == 13 * 8, "SceneRefs layout");
static_assert(sizeof(FrameParams) == 13 * 8 + 11 * 8 + 7 * 16 + 26 * 4 + SM_MAX_CLIP_PLANES * 16,
              "FrameParams layout");
static_assert(sizeof(RayDesc) == 24, "RayDesc layout");
static_assert(sizeof(Segment) == 16, "Segment layout");
static_assert(sizeof(CachedSegment) == 40, "CachedSegment layout");
static_assert(sizeof(RenderStats) == 60, "RenderStats layout");
inline uint64_t elementStepCount(const RenderStats& s) {
  return uint64_t(s.elementStepsHigh) << 32 | s.elementSteps;
}
inline uint64_t sampleCount(const RenderStats& s) {
  return uint64_t(s.samplesHigh) << 32 | s.samples;
}
}  // namespace sm::gpu
#endif

#endif
