// Transfer function and front-to-back integration of one element's samples (docs/ARCHITECTURE.md,
// "Rendering model").
#ifndef SM_TRANSFER_GLSL
#define SM_TRANSFER_GLSL

// floor(x) as an integer, for 0 <= x < 2^23 (table coordinates): added to 2^23, a float's mantissa
// holds it. Not uint(x): lavapipe converts a float to an integer one lane at a time (LLVM's
// saturating conversion, scalarised), eight conversions and compares per sample; this is a
// vector floor, add and subtract. NaN gives some large value, which the callers' min() bounds.
const float kTwo23 = 8388608.0;
const uint kTwo23Bits = 0x4B000000u;  // floatBitsToUint(kTwo23); kTwo23 + n has bits kTwo23Bits + n

uint floorIndex(float x) {
  precise float f = floor(x) + kTwo23;
  return floatBitsToUint(f) - kTwo23Bits;
}

uvec3 floorIndex(vec3 x) {
  precise vec3 f = floor(x) + vec3(kTwo23);
  return floatBitsToUint(f) - uvec3(kTwo23Bits);
}

// Entries i and min(i + 1, n - 1) of the table, interpolated. Every per-lane load is a gather on
// lavapipe, and the table's were about half of a sample's cost: the two entries are read as one
// 32-byte span of four 64-bit words (half the gathers of eight floats; the buffer is 16-byte
// aligned), from entry min(i, n - 2) (the renderer insists on n >= 2) so that the span stays in the
// table.
//
// Consecutive samples along a ray mostly fall between the same two entries (a table of 256 entries
// over the field's range, samples a fraction of an element apart), so a walk keeps the last two
// entries it read and reads again only when the interval changes: a SIMD batch skips the gathers
// when none of its rays needs them. The values used are the same either way.
struct TfCache {
  uint i;  // interval of lo and hi; kNoInterval: none yet
  vec4 lo, hi;
};

const uint kNoInterval = 0xFFFFFFFFu;

TfCache emptyTfCache() { return TfCache(kNoInterval, vec4(0.0), vec4(0.0)); }

// The transfer function maps log2(s) (tfLo and tfScale are then in log2 units): a specialisation,
// so that linear frames pay nothing for it. Values <= 0 fall below the (positive) range.
layout(constant_id = 15) const bool kLogScale = false;

vec4 transferLookupCached(FrameParams fp, float s, inout TfCache cache) {
  if (kLogScale) s = log2(max(s, 1.17549435e-38));
  float x = clamp((s - fp.tfLo) * fp.tfScale, 0.0, 1.0) * float(fp.tfEntries - 1u);
  uint i = min(floorIndex(x), fp.tfEntries - 1u);
  // Decided for the SIMD batch (a vote), and then every lane reads its entries: a lane-by-lane
  // decision would put the reads under a mask that changes from sample to sample, and on lavapipe
  // (no fast gathers on AMD CPUs) each masked read is eight branches that such a mask makes
  // unpredictable. A lane that did not need new entries reads the same ones again.
  if (smAny(i != cache.i)) {
    uint w = 2u * min(i, fp.tfEntries - 2u);
    SmUint64s tf = SmUint64s(fp.transferFunction);
    cache.hi = vec4(unpackFloats(tf.v[w + 2u]), unpackFloats(tf.v[w + 3u]));
    cache.lo = i == fp.tfEntries - 1u ? cache.hi : vec4(unpackFloats(tf.v[w]), unpackFloats(tf.v[w + 1u]));
    cache.i = i;
  }
  return mix(cache.lo, cache.hi, x - float(i));
}

vec4 transferLookup(FrameParams fp, float s) {
  TfCache none = emptyTfCache();
  return transferLookupCached(fp, s, none);
}

// t of grid sample k, computed the same way everywhere (so every rank agrees on boundaries).
float sampleT(uint k, float dt) {
  precise float t = float(k) * dt;
  return t;
}

// Smallest k with sampleT(k) >= t, at most kSampleLimit: render::finestStep refuses steps that
// would put a data point further along a ray, so only a degenerate crossing (an infinite or absurd
// t) reaches the limit, and it then ends there instead of counting forever.
const uint kSampleLimit = 16777216u;

uint firstSample(float t, float dt) {
  t = min(t, sampleT(kSampleLimit, dt));
  uint k = uint(max(ceil(t / dt), 0.0));
  while (k > 0u && sampleT(k - 1u, dt) >= t) k -= 1u;
  while (sampleT(k, dt) < t) k += 1u;
  return k;
}

layout(constant_id = 13) const bool kShading = false;

// Blinn-Phong with a headlight (light and view along -dir, so the half vector is too), two-sided:
// a gradient pointing away from the viewer lights the same as one pointing at it.
float shadingCosine(vec3 grad, vec3 dir) {
  float m = length(grad);
  return m > 0.0 && !isinf(m) ? abs(dot(grad, dir)) / m : -1.0;  // -1: no normal, unshaded
}

vec3 shade(FrameParams fp, vec3 rgb, float alpha, float c) {
  if (c < 0.0) return rgb;
  return rgb * (fp.shadeAmbient + fp.shadeDiffuse * c) + alpha * fp.shadeSpecular * pow(c, fp.shadeShininess);
}


layout(constant_id = 12) const bool kElementExact = false;

// Element-exact integration with the pre-integrated transfer function; mirrors
// PreintegrationTable::integrate (src/render/preintegration.cpp) step by step, on the device layout
// of PreintegrationTable::deviceWords (one 64-bit gather per colour corner and per cumulative
// lookup).
float piCoord(FrameParams fp, float s, uint bins) {
  float x;
  if (kLogScale)  // a log-spaced grid (PreintegrationTable::coordinate)
    x = (log2(max(s, 1.17549435e-38)) - log2(fp.piLo)) / (log2(fp.piHi) - log2(fp.piLo));
  else
    x = (s - fp.piLo) / (fp.piHi - fp.piLo);
  return clamp(x, 0.0, 1.0) * float(bins - 1u);
}

float piCumulativeAt(FrameParams fp, float s) {
  float x = piCoord(fp, s, fp.piCumulativeBins);
  uint i = min(floorIndex(x), fp.piCumulativeBins - 2u);
  vec2 pair = unpackFloats(SmUint64s(fp.piCumulative).v[i]);
  return mix(pair.x, pair.y, x - float(i));
}

// float(code) for a code below 2^23, by the mantissa trick of floorIndex (vector operations).
vec3 codeToFloat(uvec3 code) {
  return uintBitsToFloat(code | uvec3(kTwo23Bits)) - vec3(kTwo23);
}

// PreintegrationTable::decodeColor: three 21-bit channels, times 2^-21 (exact).
vec3 piColorEntry(SmUint64s table, uint i) {
  uint64_t w = table.v[i];
  const uint64_t mask = 0x1FFFFFul;
  uvec3 code = uvec3(uint(w & mask), uint((w >> 21) & mask), uint(w >> 42));
  return codeToFloat(code) * (1.0 / 2097152.0);
}

vec3 piColor(FrameParams fp, float sf, float sb, float L) {
  vec3 x = vec3(piCoord(fp, sf, fp.piScalarBins), piCoord(fp, sb, fp.piScalarBins),
                sqrt(clamp(L * fp.piSigmaMax / fp.piTauMax, 0.0, 1.0)) * float(fp.piLengthBins - 1u));
  uvec3 size = uvec3(fp.piScalarBins, fp.piScalarBins, fp.piLengthBins);
  uvec3 lo = min(floorIndex(x), size - 1u);
  uvec3 hi = min(lo + 1u, size - 1u);
  vec3 w = x - vec3(lo);
  SmUint64s table = SmUint64s(fp.preintegration);
  // Unrolled: the eight gathers are independent, so their latencies overlap.
  vec3 r = vec3(0.0);
  [[unroll]] for (uint c = 0u; c < 8u; ++c) {
    bvec3 up = bvec3((c & 1u) != 0u, (c & 2u) != 0u, (c & 4u) != 0u);
    uvec3 at = mix(lo, hi, up);
    vec3 wc = mix(1.0 - w, w, vec3(up));
    r += wc.x * wc.y * wc.z * piColorEntry(table, (at.z * size.y + at.y) * size.x + at.x);
  }
  return r;
}

// A piece whose scalar stays within [piLo, piHi].
vec4 piInside(FrameParams fp, float sf, float sb, float L) {
  float ds = sb - sf;
  float mean;
  // A branch, not a selection, so that a SIMD batch whose pieces all change enough skips the
  // transfer function's gathers. The threshold is PreintegrationTable::kSmallDelta's (why there).
  float small = kLogScale ? max(sf, sb) * log(fp.piHi / fp.piLo) : fp.piHi - fp.piLo;
  if (abs(ds) > 1e-3 * small) mean = (piCumulativeAt(fp, sb) - piCumulativeAt(fp, sf)) / ds;
  else mean = transferLookup(fp, 0.5 * (sf + sb)).a * fp.sigmaScale;
  float alpha = 1.0 - exp(-L * max(mean, 0.0));
  return vec4(piColor(fp, sf, sb, L) * alpha, alpha);
}

// A piece of length L outside [piLo, piHi], where the function is constant: closed form, from the
// end values (rgb, extinction) stored after the cumulative pairs.
vec4 piConstant(FrameParams fp, bool above, float L) {
  SmUint64s ends = SmUint64s(fp.piCumulative + 8ul * uint64_t(fp.piCumulativeBins - 1u));
  uint at = above ? 2u : 0u;
  vec4 e = vec4(unpackFloats(ends.v[at]), unpackFloats(ends.v[at + 1u]));
  float alpha = 1.0 - exp(-L * e.a);
  return vec4(e.rgb * alpha, alpha);
}

// Colour (premultiplied) and opacity of a piece of length L with the scalar running linearly from
// sf to sb: [0, c1] outside on sf's side, [c1, c2] inside the range, [c2, 1] outside on sb's side.
// The outside pieces are rare; behind branches, a SIMD batch without one skips them.
vec4 preintegrated(FrameParams fp, float sf, float sb, float L) {
  if (!(L > 0.0)) return vec4(0.0);
  // Non-finite data at either end: the whole piece in the NaN colour (its values inside are NaN
  // too, as interpolation carries a NaN vertex), transparent unless asked for.
  if (isnan(sf) || isinf(sf) || isnan(sb) || isinf(sb)) {
    float alpha = 1.0 - exp(-L * fp.nanColor.a * fp.sigmaScale);
    return vec4(fp.nanColor.rgb * alpha, alpha);
  }
  float c1, c2;
  if (sb != sf) {
    float uLo = (fp.piLo - sf) / (sb - sf), uHi = (fp.piHi - sf) / (sb - sf);
    c1 = clamp(min(uLo, uHi), 0.0, 1.0);
    c2 = clamp(max(uLo, uHi), 0.0, 1.0);
  } else {
    c1 = sf >= fp.piLo && sf <= fp.piHi ? 0.0 : 1.0;
    c2 = 1.0;
  }
  vec4 acc = vec4(0.0);
  if (c1 > 0.0) acc = piConstant(fp, sf > fp.piHi, c1 * L);
  if (c2 > c1) {
    float a = clamp(mix(sf, sb, c1), fp.piLo, fp.piHi), b = clamp(mix(sf, sb, c2), fp.piLo, fp.piHi);
    acc += (1.0 - acc.a) * piInside(fp, a, b, (c2 - c1) * L);
  }
  if (c2 < 1.0) acc += (1.0 - acc.a) * piConstant(fp, sb > fp.piHi, (1.0 - c2) * L);
  return acc;
}

// Pieces per non-tetrahedral crossing in element-exact mode: their scalar is not linear along the
// ray, so it is taken piecewise linear. Two pieces where the scalar at the crossing's midpoint is
// within kChordTolerance of the table's scale (piInside's threshold) of the chord between its
// ends; else pieces at most dt long, at least kMinPieces, an even number (the midpoint is one of
// their ends).
const uint kMinPieces = 4u;
const uint kMaxPieces = 64u;
const float kChordTolerance = 1e-4;

// Gradient of a scalar that changes by dp along the columns of J: inverse(transpose(J)) * dp.
vec3 linearGradient(mat3 J, vec3 dp) {
  if (!(abs(determinant(J)) > 0.0)) return vec3(0.0);
  return inverse(transpose(J)) * dp;
}

// World-space gradient of the scalar (for shading) in a pyramid, wedge or hexahedron, from the
// shape functions at parametric point p, mapped by the inverse transposed Jacobian. (Constant in a
// tetrahedron: the marcher computes that once per element.)
vec3 scalarGradient(uint type, vec3 X[8], float S[8], vec3 p) {
  float N[8];
  vec3 dN[8];
  shapeFunctions(type, p, N, dN);
  mat3 J = mat3(0.0);
  vec3 dp = vec3(0.0);
  [[unroll]] for (uint i = 0u; i < 8u; ++i) {
    J[0] += dN[i].x * X[i];
    J[1] += dN[i].y * X[i];
    J[2] += dN[i].z * X[i];
    dp += S[i] * dN[i];
  }
  return linearGradient(J, dp);
}

// The scalar at t on the element crossed over [tIn, tOut]: tetrahedra interpolate linearly along
// the ray between the crossing scalars (exact for linear elements); the other types evaluate their
// shape functions (Newton from the last point's parametric coordinates) everywhere. With shading,
// also the shading cosine there.
float scalarAlongRay(RayFrame fr, uint type, vec3 W0, vec3 X[8], float S[8], vec3 tetGrad, float tIn,
                     float tOut, float sIn, float sOut, float t, inout vec3 guess, out float cosine) {
  float s;
  if (type == SM_TET) {
    s = t <= tIn ? sIn : t >= tOut ? sOut : mix(sIn, sOut, (t - tIn) / (tOut - tIn));
  } else {
    // Not the crossing scalars at the ends: those interpolate over the face's triangles, which
    // differs from the cell's own (bilinear) interpolation on a quadrilateral face.
    invertIsoparametric(type, X, fr.org + t * fr.dir - W0, guess);
    s = interpolateIsoparametric(type, guess, S);
  }
  if (kShading) cosine = shadingCosine(type == SM_TET ? tetGrad : scalarGradient(type, X, S, guess), fr.dir);
  else cosine = -1.0;
  return s;
}

// What the element crossed over [tIn, tOut) adds within [a, b): its samples on the global grid,
// or in element-exact mode the whole piece, pre-integrated (shaded with the cosine at its end).
// tetGrad: a tetrahedron's gradient (shading only); g: the geometry of any other element.
// kNext: the first grid sample at or after a, or kNoSample to have it computed; on return, the
// first at or after b (elements along a walk are contiguous, so the next element starts there and
// the division and search of firstSample run once per walk, not once per element).
const uint kNoSample = 0xFFFFFFFFu;

void integrateElement(RayFrame fr, FrameParams fp, uint type, ElementGeom g, vec3 tetGrad, float tIn,
                      float tOut, float sIn, float sOut, float a, float b, inout vec3 guess, inout vec4 acc,
                      inout uint samples, inout uint kNext, inout TfCache tfc) {
  float dt = fp.dt;
  // Newton works relative to the element's first vertex: small numbers, better conditioned. Zero
  // past the element's vertices (see interpolate.glsl).
  vec3 W0 = g.W[0];
  vec3 X[8];
  float S[8];
  if (type != SM_TET) {
    uint nv = SM_NUM_VERTS[type];
    [[unroll]] for (uint i = 0u; i < 8u; ++i) {
      X[i] = i < nv ? g.W[i] - W0 : vec3(0.0);
      S[i] = i < nv ? g.S[i] : 0.0;
    }
  }
  float cosine;
  if (kElementExact) {
    if (kClip) {  // the clip planes' part of the piece, integrated as a whole piece is
      a = max(a, fr.clipLo);
      b = min(b, fr.clipHi);
      if (!(b > a)) return;
    }
    if (type == SM_TET) {  // one linear piece
      float sa = scalarAlongRay(fr, type, W0, X, S, tetGrad, tIn, tOut, sIn, sOut, a, guess, cosine);
      float sb = scalarAlongRay(fr, type, W0, X, S, tetGrad, tIn, tOut, sIn, sOut, b, guess, cosine);
      vec4 c = preintegrated(fp, sa, sb, b - a);
      if (kShading) c.rgb = shade(fp, c.rgb, c.a, cosine);
      acc += (1.0 - acc.a) * c;
      samples += 1u;
      return;
    }
    // The ends' parametric points by Newton, from the entry face's guess (stepOf) and from a step
    // along the Jacobian there; the midpoint and any other point from the straight line between
    // them in parametric space, with one Newton step. Why: a full Newton search from the previous
    // point at each of at least five points per crossing made element-exact integration cost 1.2
    // to 1.7 times the default step's time on hexahedral meshes (docs/ACCURACY.md has them).
    vec3 pa = guess;
    mat3 Jinv;
    solveIsoparametric(type, X, fr.org + a * fr.dir - W0, pa, Jinv);
    vec3 pb = clamp(pa + Jinv * ((b - a) * fr.dir), vec3(-1.0), vec3(2.0));
    solveIsoparametric(type, X, fr.org + b * fr.dir - W0, pb, Jinv);
    float sa = interpolateIsoparametric(type, pa, S), sb = interpolateIsoparametric(type, pb, S);
    float tm = mix(a, b, 0.5);
    vec3 pm = mix(pa, pb, 0.5);
    correctIsoparametric(type, X, fr.org + tm * fr.dir - W0, pm);
    float sm = interpolateIsoparametric(type, pm, S);
    float scale = kLogScale ? max(abs(sa), abs(sb)) * log(fp.piHi / fp.piLo) : fp.piHi - fp.piLo;
    uint m = 2u;
    if (!(abs(sm - 0.5 * (sa + sb)) <= kChordTolerance * scale))
      m = (clamp(uint(ceil((b - a) / dt)), kMinPieces, kMaxPieces) + 1u) & ~1u;
    float tPrev = a, sPrev = sa;
    SM_NO_UNROLL for (uint i = 1u; i <= m; ++i) {
      float t = i == m ? b : mix(a, b, float(i) / float(m));
      vec3 q = i == m ? pb : 2u * i == m ? pm : mix(pa, pb, float(i) / float(m));
      float s = i == m ? sb : sm;
      if (i != m && 2u * i != m) {
        correctIsoparametric(type, X, fr.org + t * fr.dir - W0, q);
        s = interpolateIsoparametric(type, q, S);
      }
      vec4 c = preintegrated(fp, sPrev, s, t - tPrev);
      if (kShading) c.rgb = shade(fp, c.rgb, c.a, shadingCosine(scalarGradient(type, X, S, q), fr.dir));
      acc += (1.0 - acc.a) * c;
      samples += 1u;
      if (acc.a >= fp.earlyTermination) return;
      tPrev = t;
      sPrev = s;
    }
    return;
  }
  uint k = kNext != kNoSample ? kNext : firstSample(a, dt);
  uint kEnd = max(firstSample(b, dt), k);
  kNext = kEnd;
  if (kClip) {  // the samples the clip planes keep (the grid and the walk's bookkeeping stay)
    k = max(k, fr.kClipLo);
    kEnd = max(min(kEnd, fr.kClipHi), k);
  }
  // One trip count for the SIMD batch (the most samples any of its lanes takes in its element), and
  // a lane with fewer computes samples at b that it drops: the mask inside the loop stays the walk's
  // instead of one that changes with each lane's count, which keeps the transfer function's reads
  // predictable on lavapipe (transferLookupCached says why), and the bound is one reduction per
  // element instead of a vote per sample. The samples kept, their order and values are the same.
  uint n = kEnd - k;
  uint trips = smMax(n);
  bool done = false;  // early termination, decided after a sample as the walk decides it
  for (uint j = 0u; j < trips; ++j) {
    bool more = j < n && !done;
    float t = more ? sampleT(k, dt) : b;
    vec3 kept = guess;
    float s = scalarAlongRay(fr, type, W0, X, S, tetGrad, tIn, tOut, sIn, sOut, t, guess, cosine);
    bool finite = !isnan(s) && !isinf(s);  // non-finite data takes the NaN colour
    vec4 c = transferLookupCached(fp, finite ? s : fp.tfLo, tfc);
    if (kShading) c.rgb = shade(fp, c.rgb, 1.0, cosine);
    if (!finite) c = fp.nanColor;  // opacity 0 unless asked for: transparent
    float alpha = 1.0 - exp(-c.a * fp.sigmaScale * dt);
    vec4 next;
    next.rgb = acc.rgb + (1.0 - acc.a) * alpha * c.rgb;
    next.a = acc.a + (1.0 - acc.a) * alpha;
    if (more) {
      acc = next;
      samples += 1u;
      k += 1u;
      done = acc.a >= fp.earlyTermination;
    } else {
      guess = kept;
    }
  }
}

#endif
