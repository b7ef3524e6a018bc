#version 460
// nh_denoise on the GPU (Peres 2022 §4.4, Algorithm 1), one stage a dispatch, each what
// NHDenoisePass::execute and atrousLevel compute on the CPU: the planes set up from the inputs
// (the split off pt_direct, the albedo demodulation), L̄ and each region's measured noise as
// partial sums a group reduced in one; with the variance colour weight, the variance prefilter,
// the holes prefilled and the first level's guide; then each region's levels in turn — a level
// filters the region's pixels with the 25 taps of the B-spline kernel `step` apart, in the CPU's
// order (rows, then columns), reading only sampled pixels of the centre's view, their colours
// compared by Dammertz's σ_c relative to L̄ (halved each level) or by σ_v of the guide's noise,
// and copies the others — and the output (the albedo and emission multiplied and added back).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "nh_denoise_args.h"

layout(local_size_x = 16, local_size_y = 16) in;
layout(push_constant, scalar) uniform Push { NhStagePush p; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ArgsRef {
  NhDenoiseArgs a;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Views { EyeView v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Floats { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Uints { uint v[]; };

NhDenoiseArgs A;

#include "demodulation.glsl"

shared float sums[TD_NH_GROUP];
shared uint counts[TD_NH_COUNTS];

#include "color.glsl"
vec3 at3(uint64_t b, uint i) {
  Floats f = Floats(b);
  return vec3(f.v[3u * i], f.v[3u * i + 1u], f.v[3u * i + 2u]);
}

vec3 v3eye(EyeView v) { return vec3(v.eye[0], v.eye[1], v.eye[2]); }

// The view holding pixel (x, y); -1: none.
int viewOf(int x, int y) {
  for (uint k = 0u; k < A.viewCount; ++k) {
    const EyeView v = Views(A.views).v[k];
    if (x >= v.x && x < v.x + v.width && y >= v.y && y < v.y + v.height) return int(k);
  }
  return -1;
}
// The region of pixel i: the layer (0 inner, 1 middle, 2 outer) as the mode merges them.
int regionOf(uint i) {
  const int layer = clamp(int(Floats(A.layer).v[i]), 0, 2);
  return A.regions == 0u ? 0 : A.regions == 1u ? min(layer, 1) : layer;
}
vec3 albedo(uint i) { return demodAlbedo(A.diffuse, A.depth, A.demodulate != 0u, i); }
vec3 emitted(uint i) { return demodEmitted(A.emission, A.depth, A.demodulate != 0u, i); }

struct State {
  vec3 c;
  float var, known;
  vec3 g;  // the colour weight's guide (guided only; else the colour)
  float gvar;
};
State getState(uint which, uint i) {
  Floats s = Floats(A.state[which]);
  const uint at = A.stateFloats * i;
  const vec3 c = vec3(s.v[at], s.v[at + 1u], s.v[at + 2u]);
  if (A.guided == 0u) return State(c, s.v[at + 3u], s.v[at + 4u], c, 0.0);
  return State(c, s.v[at + 3u], s.v[at + 4u], vec3(s.v[at + 5u], s.v[at + 6u], s.v[at + 7u]),
               s.v[at + 8u]);
}
void putGuide(uint which, uint i, vec3 g, float gvar) {
  Floats s = Floats(A.state[which]);
  const uint at = A.stateFloats * i;
  s.v[at + 5u] = g.x, s.v[at + 6u] = g.y, s.v[at + 7u] = g.z, s.v[at + 8u] = gvar;
}
void putState(uint which, uint i, State t) {
  Floats s = Floats(A.state[which]);
  const uint at = A.stateFloats * i;
  s.v[at] = t.c.x, s.v[at + 1u] = t.c.y, s.v[at + 2u] = t.c.z;
  s.v[at + 3u] = t.var, s.v[at + 4u] = t.known;
  if (A.guided != 0u) putGuide(which, i, t.g, t.gvar);
}
// planeLuminance.
float stateLuminance(uint which, uint i) {
  Floats s = Floats(A.state[which]);
  const uint at = A.stateFloats * i;
  precise const float l = 0.2126 * s.v[at] + 0.7152 * s.v[at + 1u] + 0.0722 * s.v[at + 2u];
  return l;
}

// The group's sum of `value` (every invocation calls it), in invocation 0's result.
float groupSum(float value) {
  const uint t = gl_LocalInvocationIndex;
  barrier();
  sums[t] = value;
  barrier();
  for (uint half_ = TD_NH_GROUP / 2u; half_ > 0u; half_ >>= 1u) {
    if (t < half_) sums[t] += sums[t + half_];
    barrier();
  }
  return sums[0];
}
void startCounts() {
  if (gl_LocalInvocationIndex < uint(TD_NH_COUNTS)) counts[gl_LocalInvocationIndex] = 0u;
  barrier();
}
void flushCounts() {
  barrier();
  if (gl_LocalInvocationIndex < uint(TD_NH_COUNTS) && counts[gl_LocalInvocationIndex] != 0u)
    atomicAdd(Uints(A.counts).v[gl_LocalInvocationIndex], counts[gl_LocalInvocationIndex]);
}
uint groupIndex() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

// The planes from the inputs (NHDenoisePass::execute's first loop) and L̄'s partial sum.
void setup(int x, int y, int view) {
  startCounts();
  float lum = 0.0, measured = 0.0;
  if (view >= 0) {
    const uint i = uint(y) * A.width + uint(x);
    const bool sampled = Floats(A.mask).v[i] > 0.0;
    const vec3 alb = albedo(i), em = emitted(i), noisy = at3(A.noisy, i);
    State s;
    // An unsampled pixel starts empty. Split: what pt_direct does not hold, over the albedo.
    precise const vec3 c = !sampled      ? vec3(0.0)
                           : A.direct != 0ul ? (noisy - at3(A.direct, i)) / alb
                                             : (noisy - em) / alb;
    s.c = c;
    const float a = luminance(alb);
    const float v = A.variance != 0ul ? Floats(A.variance).v[i] : -1.0;
    s.var = sampled && v >= 0.0 ? v / (a * a) : -1.0;
    s.known = sampled ? 1.0 : 0.0;
    s.g = s.c;
    s.gvar = 0.0;
    putState(0u, i, s);
    if (sampled && s.var >= 0.0) {  // the prefilter's fallback: the mean measured variance
      measured = s.var;
      atomicAdd(counts[TD_NH_MEASURED], 1u);
    }
    const int r = regionOf(i);
    atomicAdd(counts[TD_NH_TOTAL + r], 1u);
    if (sampled) {
      atomicAdd(counts[TD_NH_SAMPLED], 1u);
      atomicAdd(counts[TD_NH_LISTED + r], 1u);
      // L̄ of the whole estimate: with the split, pt_direct's illumination added back.
      lum = A.direct != 0ul ? luminance(c + (at3(A.direct, i) - em) / alb) : stateLuminance(0u, i);
    }
  } else if (x < int(A.width) && y < int(A.height)) {  // outside every view: never read
    putState(0u, uint(y) * A.width + uint(x), State(vec3(0.0), -1.0, 0.0, vec3(0.0), 0.0));
  }
  const float total = groupSum(lum);
  const float measuredTotal = groupSum(measured);
  if (gl_LocalInvocationIndex == 0u) {
    Floats partials = Floats(A.partials);
    const uint g = groupIndex() * uint(TD_NH_PARTIALS);
    partials.v[g] = total;
    for (uint k = 1u; k < 4u; ++k) partials.v[g + k] = 0.0;
    partials.v[g + 4u] = measuredTotal;
  }
  flushCounts();
}

// measureNoise: a listed pixel's luminance about the mean of its listed 3 x 3 neighbours on the
// same surface (normals within ~25°), squared, summed per region.
void noise(int x, int y, int view) {
  startCounts();
  float d2[3] = float[3](0.0, 0.0, 0.0);
  if (view >= 0) {
    const EyeView v = Views(A.views).v[view];
    const uint u = uint(y) * A.width + uint(x);
    Floats mask = Floats(A.mask);
    if (mask.v[u] > 0.0) {
      const vec3 nu = at3(A.normal, u);
      float m = 0.0;
      int k = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if ((dx == 0 && dy == 0) || nx < v.x || nx >= v.x + v.width || ny < v.y ||
              ny >= v.y + v.height)
            continue;
          const uint j = uint(ny) * A.width + uint(nx);
          const vec3 nj = at3(A.normal, j);
          precise const float cosN = nu.x * nj.x + nu.y * nj.y + nu.z * nj.z;
          if (mask.v[j] <= 0.0 || cosN < 0.9) continue;
          m += stateLuminance(0u, j);
          ++k;
        }
      if (k > 0) {
        const int r = regionOf(u);
        const float d = stateLuminance(0u, u) - m / float(k);
        d2[r] = d * d;
        atomicAdd(counts[TD_NH_USED + r], 1u);
      }
    }
  }
  for (int r = 0; r < 3; ++r) {
    const float total = groupSum(d2[r]);
    if (gl_LocalInvocationIndex == 0u)
      Floats(A.partials).v[groupIndex() * uint(TD_NH_PARTIALS) + 1u + uint(r)] = total;
  }
  flushCounts();
}

// One group: the partial sums in a fixed order, L̄ and the regions' mean squared noise.
void reduce() {
  const uint t = gl_LocalInvocationIndex;
  Floats partials = Floats(A.partials);
  Floats stats = Floats(A.stats);
  Uints n = Uints(A.counts);
  for (uint k = 0u; k < uint(TD_NH_PARTIALS); ++k) {
    float s = 0.0;
    for (uint g = t; g < A.groups; g += TD_NH_GROUP) s += partials.v[g * uint(TD_NH_PARTIALS) + k];
    const float total = groupSum(s);
    if (t != 0u) continue;
    if (k == 0u) {
      const uint sampled = n.v[TD_NH_SAMPLED];
      stats.v[TD_NH_MEAN] = max(sampled > 0u ? total / float(sampled) : 0.0, 1e-4);
    } else if (k == 4u) {
      const uint measured = n.v[TD_NH_MEASURED];
      stats.v[TD_NH_VAR_FALLBACK] = measured > 0u ? total / float(measured) : 0.0;
    } else {
      const uint used = n.v[TD_NH_USED + k - 1u];
      stats.v[TD_NH_NOISE_R + k - 1u] = used > 0u ? total / float(used) : 0.0;
    }
  }
}

// ---- The variance colour weight's preparation (nh_denoise.cpp).

// sameSurface: normals within ~25°, or both without a normal (the sky).
bool sameSurface(uint i, uint j) {
  if (i == j) return true;
  const vec3 ni = at3(A.normal, i), nj = at3(A.normal, j);
  precise const float cosN = ni.x * nj.x + ni.y * nj.y + ni.z * nj.z;
  precise const float li = ni.x * ni.x + ni.y * ni.y + ni.z * ni.z;
  precise const float lj = nj.x * nj.x + nj.y * nj.y + nj.z * nj.z;
  return cosN >= 0.9 || (li < 0.25 && lj < 0.25);
}
bool sampledIn(EyeView v, int x, int y) {
  return x >= v.x && x < v.x + v.width && y >= v.y && y < v.y + v.height &&
         Floats(A.mask).v[uint(y) * A.width + uint(x)] > 0.0;
}

// prefilterVariance: a sampled pixel's variance becomes the mean of the measured ones of its
// sampled 3 x 3 neighbours (the frame's mean where none measured one) or, where that is 0, the
// variance of the luminances of its surface's sampled pixels in its 5 x 5 neighbourhood (at
// least 4; about their mean, where the CPU sums moments in double). Holes' variance becomes 0.
void prefilter(int x, int y, int view) {
  const uint i = uint(y) * A.width + uint(x);
  State s = getState(p.from, i);
  if (view >= 0 && Floats(A.mask).v[i] <= 0.0) s.var = 0.0;
  if (view < 0 || Floats(A.mask).v[i] <= 0.0) {
    putState(1u - p.from, i, s);
    return;
  }
  const EyeView v = Views(A.views).v[view];
  float sum = 0.0, s1 = 0.0;
  int n = 0, m = 0;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) {
      if (!sampledIn(v, x + dx, y + dy)) continue;
      const uint j = uint(y + dy) * A.width + uint(x + dx);
      const float vj = getState(p.from, j).var;
      if (abs(dx) <= 1 && abs(dy) <= 1 && vj >= 0.0) {
        sum += vj;
        ++n;
      }
      if (!sameSurface(i, j)) continue;
      s1 += stateLuminance(p.from, j);
      ++m;
    }
  float spatial = 0.0;
  if (m >= 4) {
    const float mean = s1 / float(m);
    float d2 = 0.0;
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) {
        if (!sampledIn(v, x + dx, y + dy)) continue;
        const uint j = uint(y + dy) * A.width + uint(x + dx);
        if (!sameSurface(i, j)) continue;
        const float d = stateLuminance(p.from, j) - mean;
        d2 += d * d;
      }
    spatial = max(d2 / float(m), 0.0);
  }
  const float measured = n > 0 ? sum / float(n) : Floats(A.stats).v[TD_NH_VAR_FALLBACK];
  s.var = measured > 0.0 ? measured : spatial;
  putState(1u - p.from, i, s);
}

// prefillHoles: a hole takes, from its surface's sampled pixels in its 3 x 3 (else 5 x 5)
// neighbourhood, the estimate and variance of the one of median luminance (the CPU's
// nth_element over (luminance, index): the rank size / 2).
void prefill(int x, int y, int view) {
  const uint i = uint(y) * A.width + uint(x);
  State s = getState(p.from, i);
  if (view >= 0 && Floats(A.mask).v[i] <= 0.0) {
    const EyeView v = Views(A.views).v[view];
    float lum[25];
    uint at[25];
    int count = 0;
    for (int r = 1; r <= 2 && count == 0; ++r)
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
          if (!sampledIn(v, x + dx, y + dy)) continue;
          const uint j = uint(y + dy) * A.width + uint(x + dx);
          if (!sameSurface(i, j)) continue;
          lum[count] = stateLuminance(p.from, j);
          at[count++] = j;
        }
    for (int c = 0; c < count; ++c) {
      int rank = 0;
      for (int q = 0; q < count; ++q)
        rank += lum[q] < lum[c] || (lum[q] == lum[c] && at[q] < at[c]) ? 1 : 0;
      if (rank != count / 2) continue;
      const State t = getState(p.from, at[c]);
      s.c = t.c;
      s.var = t.var;
      s.known = 1.0;
      break;
    }
  }
  putState(1u - p.from, i, s);
}

// initGuide (in place: only the guide is written): a sampled pixel's mean over its surface's
// sampled 3 x 3 neighbours (itself included) with that mean's variance; a hole's own estimate.
void guide(int x, int y, int view) {
  const uint i = uint(y) * A.width + uint(x);
  const State s = getState(p.from, i);
  if (view < 0 || Floats(A.mask).v[i] <= 0.0) {
    putGuide(p.from, i, s.c, max(s.var, 0.0));
    return;
  }
  const EyeView v = Views(A.views).v[view];
  vec3 sum = vec3(0.0);
  float sumVar = 0.0;
  int n = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      if (!sampledIn(v, x + dx, y + dy)) continue;
      const uint j = uint(y + dy) * A.width + uint(x + dx);
      if (!sameSurface(i, j)) continue;
      const State t = getState(p.from, j);
      sum += t.c;
      sumVar += t.var;
      ++n;
    }
  putGuide(p.from, i, sum / float(n), sumVar / (float(n) * float(n)));
}

// exp(-e) as atrous.cpp's expNeg computes it (relative error < 2e-5).
float expNeg(float e) {
  precise float x = -e * 1.44269504;
  x = x < -126.0 ? -126.0 : x;
  const int xi = int(x);  // toward zero: f in (-1, 0]
  precise const float f = (x - float(xi)) * 0.69314718;
  precise const float q =
      1.0 + f * (1.0 + f * (0.5 + f * (1.0 / 6.0 +
                                       f * (1.0 / 24.0 + f * (1.0 / 120.0 + f * (1.0 / 720.0))))));
  return q * intBitsToFloat((xi + 127) << 23);
}

const float kSpline[5] = float[5](1.0 / 16.0, 1.0 / 4.0, 3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);

// atrousLevel for one centre u of the level's region: eq. 4.1 x 4.2 over the 25 taps.
void level(int x, int y, int view) {
  const uint u = uint(y) * A.width + uint(x);
  const State s = getState(p.from, u);
  if (view < 0 || regionOf(u) != p.region) {
    putState(1u - p.from, u, s);
    return;
  }
  const EyeView v = Views(A.views).v[view];
  const float mean = Floats(A.stats).v[TD_NH_MEAN];
  precise const float sc = A.sigmaColor * mean;
  const float invColor = 1.0 / max(sc * sc * ldexp(1.0, -p.iteration), 1e-20);
  const float invNormal = 1.0 / max(A.sigmaNormal * A.sigmaNormal, 1e-20);
  // Guided by variance: σ_v standard deviations of the difference of two estimates (2 var per
  // luminance, x3 for the RGB distance), floored so agreeing samples keep a little tolerance.
  precise const float floorVar = 1e-6 * mean * mean;
  precise const float sv2 = 6.0 * A.sigmaVariance * A.sigmaVariance;
  const float colorScale = s.known <= 0.0 ? 0.0
                           : A.guided != 0u ? 1.0 / (sv2 * max(s.gvar, floorVar))
                                            : invColor;
  const vec3 xu = at3(A.position, u), nu = at3(A.normal, u);
  const float z = Floats(A.depth).v[u] > 0.0 ? length(xu - v3eye(v)) : 1.0;
  precise const float sp = A.sigmaPosition * max(z, 1e-6);
  const float scale = 1.0 / (sp * sp);
  Floats mask = Floats(A.mask);
  precise vec3 sum = vec3(0.0);
  precise float sw = 0.0, sv = 0.0;
  for (int ty = 0; ty < 5; ++ty) {
    const int ny = y + (ty - 2) * p.step;
    if (ny < v.y || ny >= v.y + v.height) continue;
    for (int tx = 0; tx < 5; ++tx) {
      const int nx = x + (tx - 2) * p.step;
      if (nx < v.x || nx >= v.x + v.width) continue;
      const uint j = uint(ny) * A.width + uint(nx);
      const float b = mask.v[j];
      if (b == 0.0) continue;  // never sampled: never read (its weight is 0)
      const State t = getState(p.from, j);
      const vec3 xj = at3(A.position, j), nj = at3(A.normal, j);
      precise const vec3 dc = t.g - s.g, dn = nj - nu, dx = xj - xu;
      precise const float e = (dc.x * dc.x + dc.y * dc.y + dc.z * dc.z) * colorScale +
                              (dn.x * dn.x + dn.y * dn.y + dn.z * dn.z) * invNormal +
                              (dx.x * dx.x + dx.y * dx.y + dx.z * dx.z) * scale;
      precise const float w = kSpline[ty] * kSpline[tx] * b * expNeg(e);
      sum += w * t.c;
      sw += w;
      sv += w * w * t.var;
    }
  }
  if (A.guided != 0u && mask.v[u] <= 0.0 && s.known > 0.0) {
    // A hole's own (prefilled) estimate is its centre tap: otherwise taps its colour weight all
    // but rejected would, normalised, take it over.
    const float k = kSpline[2] * kSpline[2];
    sum += k * s.c;
    sv += k * k * s.var;
    sw += k;
  }
  // No usable tap (or weights so small their reciprocal would overflow): keep the value.
  if (!(sw > 1e-30)) {
    putState(1u - p.from, u, s);
    return;
  }
  precise const float inv = 1.0 / sw;
  // The filtered estimate is the next level's guide.
  const vec3 c = sum * inv;
  const float var = sv * inv * inv;
  putState(1u - p.from, u, State(c, var, 1.0, c, var));
}

void writeOutput(int x, int y, int view) {
  const uint i = uint(y) * A.width + uint(x);
  vec3 c = vec3(0.0);
  if (view >= 0) {
    const State s = getState(p.from, i);
    const vec3 alb = albedo(i);
    // Split: the filtered rest on top of the direct light (light is never negative).
    precise const vec3 lit = s.c * alb;
    c = A.direct != 0ul ? max(lit + at3(A.direct, i), vec3(0.0)) : lit + emitted(i);
  }
  Floats out3 = Floats(A.denoised);
  out3.v[3u * i] = c.x, out3.v[3u * i + 1u] = c.y, out3.v[3u * i + 2u] = c.z;
}

void main() {
  A = ArgsRef(p.args).a;
  if (p.stage == TD_NH_REDUCE) {
    reduce();
    return;
  }
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  const bool inside = x < int(A.width) && y < int(A.height);
  const int view = inside ? viewOf(x, y) : -1;
  // The setup and noise stages reduce over the group: every invocation takes part.
  if (p.stage == TD_NH_SETUP) {
    setup(x, y, view);
  } else if (p.stage == TD_NH_NOISE) {
    noise(x, y, view);
  } else if (inside) {
    if (p.stage == TD_NH_LEVEL)
      level(x, y, view);
    else if (p.stage == TD_NH_PREFILTER)
      prefilter(x, y, view);
    else if (p.stage == TD_NH_PREFILL)
      prefill(x, y, view);
    else if (p.stage == TD_NH_GUIDE)
      guide(x, y, view);
    else
      writeOutput(x, y, view);
  }
}
