#version 460
// dof_composite on the GPU, as DofCompositePass::execute (Tan et al. 2022 §3.3, eq. 7): the sharp
// raster colour in the zone of focus unless a blurred foreground reaches over the pixel, the
// traced near field with the post-process colour on bright bokeh, the far field by hit ratio, and
// the full-resolution gather of the sharp image below fine_coc where nothing nearer spreads.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "dof_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { DofCompositeArgs a; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Floats { float v[]; };

const float kZoneOfFocusCoc = 1.41421356;
const float kSilhouette = 0.02;
const int kMaxReach = 33;  // fine_coc's largest radius (dof_composite.cpp)

vec3 load3(uint64_t b, uint i) {
  Floats f = Floats(b);
  return vec3(f.v[i], f.v[i + 1u], f.v[i + 2u]);
}
float saturate(float x) { return clamp(x, 0.0, 1.0); }
float smoothstepCpu(float e0, float e1, float x) {  // dof::smoothstep
  precise const float t = saturate((x - e0) / (e1 - e0));
  precise const float r = t * t * (3.0 - 2.0 * t);
  return r;
}
vec3 lerpCpu(vec3 p, vec3 q, float t) {  // core/math.h lerp
  precise const vec3 r = p + (q - p) * t;
  return r;
}

// fineGather: the sharp image over a disc of `radius` pixels around (x, y), each neighbour
// weighted by the disc's cover and by whether its own blur reaches the centre.
vec3 fineGather(int x, int y, float radius) {
  Floats sharp = Floats(a.sharp), coc = Floats(a.coc);
  const int W = int(a.width), H = int(a.height);
  precise const float reach = radius + 0.5;
  const int r = min(int(ceil(reach)), kMaxReach);
  precise vec3 sum = vec3(0.0);
  precise float wsum = 0.0;
  for (int dy = max(-r, -y); dy <= min(r, H - 1 - y); ++dy) {
    precise const float left = max(reach * reach - float(dy * dy), 0.0);
    const int span = int(sqrt(left));
    const int x0 = max(x - span, 0), x1 = min(x + span, W - 1);
    const uint row = uint((y + dy) * W);
    for (int xx = x0; xx <= x1; ++xx) {
      const int dx = xx - x;
      const float d = sqrt(float(dx * dx + dy * dy));
      precise const float wt =
          saturate(reach - d) * saturate(0.5 * abs(coc.v[row + uint(xx)]) + 0.5 - d);
      sum += load3(a.sharp, 3u * (row + uint(xx))) * wt;
      wsum += wt;
    }
  }
  precise const float inv = 1.0 / wsum;
  return sum * inv;
}

void main() {
  const uint x = gl_GlobalInvocationID.x, y = gl_GlobalInvocationID.y;
  if (x >= a.width || y >= a.height) return;
  const uint i = y * a.width + x;
  const float c = Floats(a.coc).v[i];
  float r[TD_COMPOSITE_RT_CHANNELS];
  for (uint k = 0u; k < TD_COMPOSITE_RT_CHANNELS; ++k) r[k] = 0.0;
  if (a.rt != 0ul) {  // sampleBilinearN<9> of rt_recon at the pixel's centre
    Floats rt = Floats(a.rt);
    const int w = int(a.rtWidth), h = int(a.rtHeight);
    precise const float fx = max((float(x) + 0.5) * a.scaleX - 0.5, -1.0);
    precise const float fy = max((float(y) + 0.5) * a.scaleY - 0.5, -1.0);
    const int x0 = int(fx + 1.0) - 1, y0 = int(fy + 1.0) - 1;
    precise const float tx = fx - float(x0), ty = fy - float(y0);
    const int xa = clamp(x0, 0, w - 1), xb = clamp(x0 + 1, 0, w - 1);
    const int ya = clamp(y0, 0, h - 1), yb = clamp(y0 + 1, 0, h - 1);
    const uint C = TD_COMPOSITE_RT_CHANNELS;
    for (uint k = 0u; k < C; ++k) {
      const float p00 = rt.v[C * uint(ya * w + xa) + k], p10 = rt.v[C * uint(ya * w + xb) + k];
      const float p01 = rt.v[C * uint(yb * w + xa) + k], p11 = rt.v[C * uint(yb * w + xb) + k];
      precise const float s =
          (p00 * (1.0 - tx) + p10 * tx) * (1.0 - ty) + (p01 * (1.0 - tx) + p11 * tx) * ty;
      r[k] = s;
    }
  }
  // dof::RtChannels: rgb 0, coc 3, hit 4, coverage 5, near 6.
  const float coverage = saturate(r[5]);
  precise const float invCoverage = 1.0 / max(r[5], 1e-6);
  const vec3 rtc = coverage > 0.0 ? vec3(r[0], r[1], r[2]) * invCoverage : vec3(0.0);
  const float hit = coverage > 0.0 ? r[4] / max(r[5], 1e-6) : 0.0;
  const vec3 rtNear = coverage > 0.0 ? vec3(r[6], r[7], r[8]) * invCoverage : vec3(0.0);
  const bool inFocus = abs(c) < kZoneOfFocusCoc;
  const bool hasBokeh = a.bokeh != 0ul;
  const float intensity = hasBokeh ? Floats(a.bokeh).v[2u * i] : 0.0;
  const float foreground = hasBokeh ? Floats(a.bokeh).v[2u * i + 1u] : 0.0;
  // A blurred foreground reaches over this pixel: some of its lens rays hit the near field, or
  // (without rays) the gather drew from foreground taps.
  const bool silhouette = coverage > 0.0 ? hit > kSilhouette : hasBokeh && foreground > kSilhouette;
  const vec3 sharp = load3(a.sharp, 3u * i);
  const vec3 pp = a.postfx != 0ul ? load3(a.postfx, 3u * i) : sharp;
  vec3 col;
  if (a.rtMode != 0u) {
    col = lerpCpu(sharp, rtc, coverage);
  } else if (inFocus && !silhouette) {
    col = sharp;
  } else if (inFocus && a.sharpBackground != 0u) {
    col = lerpCpu(pp, lerpCpu(sharp, rtNear, hit), coverage);
  } else {
    vec3 traced;
    if (c < 0.0)  // near field: ray traced, post-process on bright bokeh
      traced = a.useBokeh != 0u && hasBokeh ? lerpCpu(rtc, pp, intensity) : rtc;
    else  // far field, eq. 7
      traced = lerpCpu(rtc, pp, smoothstepCpu(0.0, a.farBlend, hit));
    col = lerpCpu(pp, traced, coverage);
    const float ac = abs(c);
    const bool noForeground =
        hasBokeh && foreground <= kSilhouette && (c < 0.0 || coverage <= 0.0 || hit <= kSilhouette);
    if (ac < a.fineCoc && noForeground)
      col = lerpCpu(col, fineGather(int(x), int(y), 0.5 * ac),
                    1.0 - smoothstepCpu(0.5 * a.fineCoc, a.fineCoc, ac));
  }
  Floats result = Floats(a.dof);
  result.v[3u * i] = col.x;
  result.v[3u * i + 1u] = col.y;
  result.v[3u * i + 2u] = col.z;
}
