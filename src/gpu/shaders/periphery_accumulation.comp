#version 460
// periphery_accumulation on the GPU, one invocation a pixel, what
// PeripheryAccumulationPass::execute computes: a listed pixel of the accumulated layers blends
// this frame's illumination into its history reprojected by the motion vectors (bilinear over
// the history pixels of its eye that saw the same surface), an unlisted one takes its history
// alone (fill_unlisted); the fovea keeps this frame's samples.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "foveated_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { uint64_t args; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ArgsRef {
  PeripheryArgs a;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Views { EyeView v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Floats { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Counters {
  PeripheryCounters c;
};

PeripheryArgs A;

#include "demodulation.glsl"

// HistoryChannels: illumination rgb, frames, world position, normal.
const uint kFrames = 3u, kPosition = 4u, kNormal = 7u, kChannels = 10u;

vec3 at3(uint64_t b, uint i) {
  Floats f = Floats(b);
  return vec3(f.v[3u * i], f.v[3u * i + 1u], f.v[3u * i + 2u]);
}
vec3 history3(uint64_t b, uint i, uint c) {
  Floats f = Floats(b);
  const uint at = kChannels * i + c;
  return vec3(f.v[at], f.v[at + 1u], f.v[at + 2u]);
}

// Where the pixel was last frame, from those of the four history pixels around it that saw the
// same surface: illumination rgb and frames; false under a quarter of the footprint.
bool reproject(EyeView v, int x, int y, vec3 p, vec3 nrm, out vec4 hist) {
  const uint i = uint(y) * A.width + uint(x);
  Floats motion = Floats(A.motion);
  const float bx = float(x) - motion.v[2u * i], by = float(y) - motion.v[2u * i + 1u];
  const int ix = int(floor(bx)), iy = int(floor(by));
  const float tx = bx - float(ix), ty = by - float(iy);
  const vec3 eye = vec3(v.eye[0], v.eye[1], v.eye[2]);
  const float limit = A.positionTolerance * length(p - eye);
  float wsum = 0.0;
  hist = vec4(0.0);
  Floats prev = Floats(A.previous);
  for (int j = 0; j < 2; ++j)
    for (int k = 0; k < 2; ++k) {
      const float w = (k != 0 ? tx : 1.0 - tx) * (j != 0 ? ty : 1.0 - ty);
      const int hx = ix + k, hy = iy + j;
      if (w <= 0.0 || hx < v.x || hx >= v.x + v.width || hy < v.y || hy >= v.y + v.height) continue;
      const uint h = uint(hy) * A.width + uint(hx);
      if (prev.v[kChannels * h + kFrames] <= 0.0 ||
          length(history3(A.previous, h, kPosition) - p) > limit ||
          dot(history3(A.previous, h, kNormal), nrm) < A.minCos)
        continue;
      for (uint c = 0u; c < 4u; ++c) hist[c] += w * prev.v[kChannels * h + c];
      wsum += w;
    }
  if (wsum < 0.25) return false;
  hist /= wsum;
  return true;
}

void main() {
  A = ArgsRef(args).a;
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  int view = -1;
  for (uint k = 0u; k < A.viewCount && view < 0; ++k) {
    const EyeView e = Views(A.views).v[k];
    if (x >= e.x && x < e.x + e.width && y >= e.y && y < e.y + e.height) view = int(k);
  }
  if (view < 0) return;
  const EyeView v = Views(A.views).v[view];
  const uint i = uint(y) * A.width + uint(x);
  Floats history = Floats(A.history), accum = Floats(A.accum);
  const bool demodulate = (A.flags & TD_PERIPHERY_DEMODULATE) != 0u;
  const bool listed = Floats(A.mask).v[i] > 0.0;
  const int layer = int(Floats(A.layer).v[i]);
  const bool accumulated = A.previous != 0ul && layer >= A.fromLayer && Floats(A.depth).v[i] > 0.0;
  const vec3 p = at3(A.position, i), nrm = at3(A.normal, i);
  vec4 hist = vec4(0.0);
  const bool fill = (A.flags & TD_PERIPHERY_FILL) != 0u;
  const bool reprojected = accumulated && (listed || fill) && reproject(v, x, y, p, nrm, hist);
  if (!listed && !reprojected) {
    for (uint c = 0u; c < kChannels; ++c) history.v[kChannels * i + c] = 0.0;
    accum.v[3u * i] = 0.0, accum.v[3u * i + 1u] = 0.0, accum.v[3u * i + 2u] = 0.0;
    Floats(A.accumVariance).v[i] = -1.0;
    Floats(A.accumMask).v[i] = 0.0;
    return;
  }
  const vec3 alb = demodAlbedo(A.diffuse, A.depth, demodulate, i);
  const vec3 em = demodEmitted(A.emission, A.depth, demodulate, i);
  // In illumination units: this frame's sample where listed, else the history alone.
  vec3 result = hist.xyz;
  float n = hist.w;
  if (listed) {
    const vec3 c = (at3(A.noisy, i) - em) / alb;
    result = c;
    n = 1.0;
  }
  if (listed && reprojected) {
    const float alpha = max(1.0 / (hist.w + 1.0), A.alphaMin);
    const vec3 blended = hist.xyz * (1.0 - alpha) + result * alpha;
    result = blended;
    n = min(hist.w + 1.0, 1.0 / A.alphaMin);
  }
  const vec3 colour = result * alb + em;
  accum.v[3u * i] = colour.x, accum.v[3u * i + 1u] = colour.y, accum.v[3u * i + 2u] = colour.z;
  Floats(A.accumMask).v[i] = 1.0;
  // The mean of n frames: this frame's variance over n.
  const float var = A.variance != 0ul && listed ? Floats(A.variance).v[i] : -1.0;
  Floats(A.accumVariance).v[i] = var >= 0.0 ? var / n : -1.0;
  const uint h = kChannels * i;
  history.v[h] = result.x, history.v[h + 1u] = result.y, history.v[h + 2u] = result.z;
  history.v[h + kFrames] = n;
  history.v[h + kPosition] = p.x, history.v[h + kPosition + 1u] = p.y;
  history.v[h + kPosition + 2u] = p.z;
  history.v[h + kNormal] = nrm.x, history.v[h + kNormal + 1u] = nrm.y;
  history.v[h + kNormal + 2u] = nrm.z;
  if (layer >= A.fromLayer) {
    Counters c = Counters(A.counters);
    atomicAdd(c.c.framesSum, uint64_t(n * 65536.0));
    atomicAdd(c.c.pixels, 1ul);
  }
}
