#version 460
// postfx_dof on the GPU (Tan et al. 2022 §3.1), one stage a dispatch, each what PostfxDofPass's
// step does on the CPU, operation for operation: downsample (CoC: the nearest of four; the
// highlight flag), the tiles' max |CoC| and its 3x3 neighbourhood max, the 9-tap bilateral
// prefilter, the 81-tap gather (eq. 1; the taps and the aperture's extents from the host, so both
// devices round the same offsets), the 3x3 median and the bilinear upscale.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "dof_args.h"
#include "image_filters.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { DofStagePush p; };
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Args { PostfxDofArgs a; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Floats { float v[]; };

const float kPi = 3.14159265358979323846;
const float kZoneOfFocusCoc = 1.41421356;

#include "color.glsl"

vec3 load3(uint64_t b, uint i) {
  Floats f = Floats(b);
  return vec3(f.v[i], f.v[i + 1u], f.v[i + 2u]);
}

// sampleBilinearN<3> (core/image_filters.h) of a w x h, 3-channel buffer.
vec3 bilinear3(uint64_t b, int w, int h, float x, float y) {
  precise const float fx = max(x - 0.5, -1.0), fy = max(y - 0.5, -1.0);
  const int x0 = int(fx + 1.0) - 1, y0 = int(fy + 1.0) - 1;
  precise const float tx = fx - float(x0), ty = fy - float(y0);
  const int xa = clamp(x0, 0, w - 1), xb = clamp(x0 + 1, 0, w - 1);
  const int ya = clamp(y0, 0, h - 1), yb = clamp(y0 + 1, 0, h - 1);
  const vec3 p00 = load3(b, 3u * uint(ya * w + xa)), p10 = load3(b, 3u * uint(ya * w + xb));
  const vec3 p01 = load3(b, 3u * uint(yb * w + xa)), p11 = load3(b, 3u * uint(yb * w + xb));
  precise const vec3 r =
      (p00 * (1.0 - tx) + p10 * tx) * (1.0 - ty) + (p01 * (1.0 - tx) + p11 * tx) * ty;
  return r;
}

// std::lround: halves away from zero (v - trunc(v) is exact, unlike v + 0.5).
int roundAway(float v) {
  const float t = trunc(v);
  return int(t) + (abs(v - t) >= 0.5 ? (v < 0.0 ? -1 : 1) : 0);
}

float saturate(float x) { return clamp(x, 0.0, 1.0); }

void downsample(PostfxDofArgs a, uint x, uint y) {
  Floats coc = Floats(a.coc);
  const int W = int(a.width), H = int(a.height);
  float cmin = uintBitsToFloat(0x7f800000u), highlight = 0.0;  // +inf
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int sx = min(2 * int(x) + i, W - 1), sy = min(2 * int(y) + j, H - 1);
      const uint k = uint(sy * W + sx);
      cmin = min(cmin, coc.v[k]);
      if (luminance(load3(a.specular, 4u * k)) >= a.specularThreshold &&
          luminance(load3(a.hdr, 3u * k)) >= a.bokehLuminance)
        highlight = 1.0;
    }
  // CoC -> view depth (the inverse of ThinLens::coc); the sky far but finite.
  precise const float den = a.lensK - cmin * a.focus;
  precise const float z = den > 1e-9 ? a.lensK * a.focus / den : 1e30;
  precise const float radius = 0.25 * abs(cmin);
  Floats h = Floats(a.halfSamples);
  const uint o = TD_HALF_SAMPLE * (y * a.halfWidth + x);
  h.v[o] = 0.0;
  h.v[o + 1u] = 0.0;
  h.v[o + 2u] = 0.0;
  h.v[o + 3u] = 0.5 * cmin;
  h.v[o + 4u] = z;
  h.v[o + 5u] = highlight;
  h.v[o + 6u] = radius;
  precise const float alpha = 1.0 / (kPi * max(radius * radius, 0.25));
  h.v[o + 7u] = alpha;
}

void tileMax(PostfxDofArgs a, uint tx, uint ty) {
  Floats h = Floats(a.halfSamples);
  float m = 0.0;
  const uint y1 = min((ty + 1u) * TD_POSTFX_TILE, a.halfHeight);
  const uint x1 = min((tx + 1u) * TD_POSTFX_TILE, a.halfWidth);
  for (uint y = ty * TD_POSTFX_TILE; y < y1; ++y)
    for (uint x = tx * TD_POSTFX_TILE; x < x1; ++x)
      m = max(m, abs(h.v[TD_HALF_SAMPLE * (y * a.halfWidth + x) + 3u]));
  Floats(a.tileMax).v[ty * a.tilesX + tx] = m;
}

void neighbourMax(PostfxDofArgs a, uint tx, uint ty) {
  Floats t = Floats(a.tileMax);
  float m = 0.0;
  const int X = int(a.tilesX), Y = int(a.tilesY);
  for (int j = max(int(ty) - 1, 0); j <= min(int(ty) + 1, Y - 1); ++j)
    for (int i = max(int(tx) - 1, 0); i <= min(int(tx) + 1, X - 1); ++i)
      m = max(m, t.v[uint(j * X + i)]);
  Floats(a.neighbourMax).v[ty * a.tilesX + tx] = m;
}

float maxCocAt(PostfxDofArgs a, uint x, uint y) {
  return Floats(a.neighbourMax).v[(y / TD_POSTFX_TILE) * a.tilesX + x / TD_POSTFX_TILE];
}

void prefilter(PostfxDofArgs a, uint x, uint y) {
  Floats h = Floats(a.halfSamples), coc = Floats(a.coc), dirs = Floats(a.taps);
  const uint o = TD_HALF_SAMPLE * (y * a.halfWidth + x);
  const float c0 = h.v[o + 3u];
  precise const float radius = 0.5 * max(2.0 * maxCocAt(a, x, y) / 8.0, kZoneOfFocusCoc);
  const float cx = 2.0 * float(x) + 1.0, cy = 2.0 * float(y) + 1.0;
  const int W = int(a.width), H = int(a.height);
  precise vec3 sum = vec3(0.0);
  precise float wsum = 0.0;
  for (uint t = 0u; t < 9u; ++t) {
    // The eight directions' cosines and sines, after the taps.
    const uint d = TD_POSTFX_TAPS * TD_TAP_FLOATS + 2u * t;
    precise const float px = t == 8u ? cx : cx + radius * dirs.v[d];
    precise const float py = t == 8u ? cy : cy + radius * dirs.v[d + 1u];
    const vec3 rgb = bilinear3(a.hdr, W, H, px, py);
    const float tc = 0.5 * coc.v[uint(clamp(int(py), 0, H - 1) * W + clamp(int(px), 0, W - 1))];
    precise const float w = 1.0 / (1.0 + abs(tc - c0));
    sum += w * rgb;
    wsum += w;
  }
  precise const vec3 rgb = sum / wsum;
  h.v[o] = rgb.x;
  h.v[o + 1u] = rgb.y;
  h.v[o + 2u] = rgb.z;
}

void gather(PostfxDofArgs a, uint x, uint y) {
  Floats pre = Floats(a.halfSamples), taps = Floats(a.taps);
  Floats gathered = Floats(a.gathered), bokeh = Floats(a.bokeh);
  const uint i0 = y * a.halfWidth + x;
  const uint o = TD_HALF_SAMPLE * i0;
  const vec3 c0 = vec3(pre.v[o], pre.v[o + 1u], pre.v[o + 2u]);
  const float z0 = pre.v[o + 4u], r0 = pre.v[o + 6u];
  precise const float R = 0.5 * maxCocAt(a, x, y);
  if (R < 0.5) {  // the whole neighbourhood is sharp
    gathered.v[3u * i0] = c0.x;
    gathered.v[3u * i0 + 1u] = c0.y;
    gathered.v[3u * i0 + 2u] = c0.z;
    bokeh.v[2u * i0] = 0.0;
    bokeh.v[2u * i0 + 1u] = 0.0;
    return;
  }
  const float nearFieldCoc = -0.5 * kZoneOfFocusCoc;  // half-res pixels
  const int hw = int(a.halfWidth), hh = int(a.halfHeight);
  precise vec3 f = vec3(0.0);
  precise float wsum = 0.0, wfSum = 0.0, spec = 0.0, reach = 0.0;
  for (uint i = 0u; i < TD_POSTFX_TAPS; ++i) {
    const uint t = TD_TAP_FLOATS * i;
    const int dx = roundAway(taps.v[t] * R), dy = roundAway(taps.v[t + 1u] * R);
    precise const float dist = taps.v[t + 2u] * R;
    const uint s = TD_HALF_SAMPLE * uint(clamp(int(y) + dy, 0, hh - 1) * hw +
                                         clamp(int(x) + dx, 0, hw - 1));
    const float sz = pre.v[s + 4u], scoc = pre.v[s + 3u], sradius = pre.v[s + 6u];
    const float salpha = pre.v[s + 7u];
    // Foreground: nearer than the centre by more than the depth range (soft over one range).
    precise const float fgShare = a.depthRange > 0.0 ? saturate((z0 - sz) * a.invRange - 1.0)
                                                     : (sz < z0 ? 1.0 : 0.0);
    const float e = scoc < 0.0 ? taps.v[t + 4u] : taps.v[t + 3u];
    precise const float dFg = i == 0u ? 1.0 : saturate(sradius * e - dist + 0.5);
    precise const float dBg = i == 0u ? 1.0 : saturate(min(sradius, r0) * e - dist + 0.5);
    precise const float dd = dBg + fgShare * (dFg - dBg);
    precise const float w = dd * salpha;
    f += w * vec3(pre.v[s], pre.v[s + 1u], pre.v[s + 2u]);
    wsum += w;
    if (i > 0u && scoc < nearFieldCoc) wfSum += fgShare * dFg * salpha;  // blurred foreground
    reach += dd;
    spec += dd * pre.v[s + 5u];
  }
  precise const float inv = 1.0 / max(wsum, 1e-20);
  gathered.v[3u * i0] = f.x * inv;
  gathered.v[3u * i0 + 1u] = f.y * inv;
  gathered.v[3u * i0 + 2u] = f.z * inv;
  bokeh.v[2u * i0] = reach > 0.0 ? spec / reach : 0.0;
  bokeh.v[2u * i0 + 1u] = wsum > 0.0 ? wfSum / wsum : 0.0;
}


void median(PostfxDofArgs a, uint x, uint y) {
  Floats g = Floats(a.gathered), filtered = Floats(a.filtered);
  const int W = int(a.halfWidth), H = int(a.halfHeight);
  for (uint c = 0u; c < 3u; ++c) {
    float v[9];
    int n = 0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int sx = clamp(int(x) + dx, 0, W - 1), sy = clamp(int(y) + dy, 0, H - 1);
        v[n++] = g.v[3u * uint(sy * W + sx) + c];
      }
    filtered.v[3u * (y * a.halfWidth + x) + c] = median9(v);
  }
}

// resizeBilinear: sampleBilinear of the half-res `src` at each frame pixel's centre.
void upscale(PostfxDofArgs a, uint x, uint y) {
  Floats src = Floats(a.src), dst = Floats(a.dst);
  const int w = int(a.halfWidth), h = int(a.halfHeight);
  const uint C = a.channels;
  const float sx = float(a.halfWidth) / float(a.width), sy = float(a.halfHeight) / float(a.height);
  precise const float fx = (float(x) + 0.5) * sx - 0.5, fy = (float(y) + 0.5) * sy - 0.5;
  const int x0 = int(floor(fx)), y0 = int(floor(fy));
  precise const float tx = fx - float(x0), ty = fy - float(y0);
  const int xa = clamp(x0, 0, w - 1), xb = clamp(x0 + 1, 0, w - 1);
  const int ya = clamp(y0, 0, h - 1), yb = clamp(y0 + 1, 0, h - 1);
  for (uint c = 0u; c < C; ++c) {
    const float p00 = src.v[C * uint(ya * w + xa) + c], p10 = src.v[C * uint(ya * w + xb) + c];
    const float p01 = src.v[C * uint(yb * w + xa) + c], p11 = src.v[C * uint(yb * w + xb) + c];
    precise const float r =
        (p00 * (1.0 - tx) + p10 * tx) * (1.0 - ty) + (p01 * (1.0 - tx) + p11 * tx) * ty;
    dst.v[C * (y * a.width + x) + c] = r;
  }
}

void main() {
  const PostfxDofArgs a = Args(p.args).a;
  const uint x = gl_GlobalInvocationID.x, y = gl_GlobalInvocationID.y;
  if (p.stage == TD_POSTFX_TILE_MAX || p.stage == TD_POSTFX_NEIGHBOUR_MAX) {
    if (x >= a.tilesX || y >= a.tilesY) return;
    if (p.stage == TD_POSTFX_TILE_MAX)
      tileMax(a, x, y);
    else
      neighbourMax(a, x, y);
    return;
  }
  if (p.stage == TD_POSTFX_UPSCALE) {
    if (x < a.width && y < a.height) upscale(a, x, y);
    return;
  }
  if (x >= a.halfWidth || y >= a.halfHeight) return;
  if (p.stage == TD_POSTFX_DOWNSAMPLE)
    downsample(a, x, y);
  else if (p.stage == TD_POSTFX_PREFILTER)
    prefilter(a, x, y);
  else if (p.stage == TD_POSTFX_GATHER)
    gather(a, x, y);
  else if (p.stage == TD_POSTFX_MEDIAN)
    median(a, x, y);
}
