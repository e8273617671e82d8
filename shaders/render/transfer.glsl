// Transfer function and front-to-back integration of one element's samples (docs/ARCHITECTURE.md,
// "Rendering model").
#ifndef SM_TRANSFER_GLSL
#define SM_TRANSFER_GLSL

vec4 transferLookup(FrameParams fp, float s) {
  float x = clamp((s - fp.tfLo) * fp.tfScale, 0.0, 1.0) * float(fp.tfEntries - 1u);
  uint i = min(uint(x), fp.tfEntries - 1u);
  uint j = min(i + 1u, fp.tfEntries - 1u);
  SmVec4s tf = SmVec4s(fp.transferFunction);
  return mix(tf.v[i], tf.v[j], x - float(i));
}

// t of grid sample k, computed the same way everywhere (so every rank agrees on boundaries).
float sampleT(uint k, float dt) {
  precise float t = float(k) * dt;
  return t;
}

// Smallest k with sampleT(k) >= t.
uint firstSample(float t, float dt) {
  uint k = uint(max(ceil(t / dt), 0.0));
  while (k > 0u && sampleT(k - 1u, dt) >= t) k -= 1u;
  while (sampleT(k, dt) < t) k += 1u;
  return k;
}

void addSample(FrameParams fp, float s, inout vec4 acc) {
  if (isnan(s) || isinf(s)) return;  // non-finite data renders transparent
  vec4 c = transferLookup(fp, s);
  float alpha = 1.0 - exp(-c.a * fp.sigmaScale * fp.dt);
  acc.rgb += (1.0 - acc.a) * alpha * c.rgb;
  acc.a += (1.0 - acc.a) * alpha;
}

// Samples of the element crossed over [tIn, tOut) that lie in [a, b). Tetrahedra interpolate
// linearly along the ray between the crossing scalars (exact for linear elements); the other types
// evaluate their shape functions at the sample point.
void integrateElement(RayFrame fr, FrameParams fp, uint type, ElementGeom g, float tIn, float tOut, float sIn,
                      float sOut, float a, float b, inout vec3 guess, inout vec4 acc, inout uint samples) {
  float dt = fp.dt;
  // Newton works relative to the element's first vertex: small numbers, better conditioned.
  vec3 X[8];
  if (type != SM_TET)
    for (uint i = 0u; i < 8u; ++i) X[i] = g.W[i] - g.W[0];
  for (uint k = firstSample(a, dt); sampleT(k, dt) < b; ++k) {
    float t = sampleT(k, dt);
    float s;
    if (type == SM_TET) {
      float len = tOut - tIn;
      s = len > 0.0 ? mix(sIn, sOut, clamp((t - tIn) / len, 0.0, 1.0)) : sIn;
    } else {
      vec3 x = fr.org + t * fr.dir - g.W[0];
      invertIsoparametric(type, X, x, guess);
      s = interpolateIsoparametric(type, guess, g.S);
    }
    addSample(fp, s, acc);
    samples += 1u;
    if (acc.a >= fp.earlyTermination) return;
  }
}

#endif
