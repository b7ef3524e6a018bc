#version 460
// taa on the GPU, pixel for pixel what TAAPass::execute computes: reprojection through the
// motion vectors (Catmull-Rom or bilinear), the YCoCg 3x3 neighbourhood clamp within the pixel's
// view, and the luma-weighted blend.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "taa_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Floats { float v[]; };
layout(push_constant, scalar) uniform Push { TaaArgs a; };

vec3 rgb(uint64_t buf, int x, int y) {
  const uint i = (uint(y) * a.width + uint(x)) * 3u;
  return vec3(Floats(buf).v[i], Floats(buf).v[i + 1u], Floats(buf).v[i + 2u]);
}

vec3 toYCoCg(vec3 c) {
  return vec3(0.25 * c.x + 0.5 * c.y + 0.25 * c.z, 0.5 * c.x - 0.5 * c.z,
              -0.25 * c.x + 0.5 * c.y - 0.25 * c.z);
}
vec3 fromYCoCg(vec3 y) { return vec3(y.x + y.y - y.z, y.x + y.z, y.x - y.y - y.z); }

void catmullRomWeights(float t, out float w[4]) {
  w[0] = t * (-0.5 + t * (1.0 - 0.5 * t));
  w[1] = 1.0 + t * t * (-2.5 + 1.5 * t);
  w[2] = t * (0.5 + t * (2.0 - 1.5 * t));
  w[3] = t * t * (-0.5 + 0.5 * t);
}

// image_filters' sampleCatmullRom over the whole frame (taps clamped to it).
vec3 catmullRom(float x, float y) {
  const float fx = x - 0.5, fy = y - 0.5;
  const int x1 = int(floor(fx)), y1 = int(floor(fy));
  float wx[4], wy[4];
  catmullRomWeights(fx - float(x1), wx);
  catmullRomWeights(fy - float(y1), wy);
  vec3 s = vec3(0.0);
  for (int j = 0; j < 4; ++j) {
    const int yy = clamp(y1 - 1 + j, 0, int(a.height) - 1);
    vec3 row = vec3(0.0);
    for (int i = 0; i < 4; ++i)
      row += wx[i] * rgb(a.history, clamp(x1 - 1 + i, 0, int(a.width) - 1), yy);
    s += wy[j] * row;
  }
  return s;
}

vec3 bilinear(float x, float y) {
  const float fx = x - 0.5, fy = y - 0.5;
  const int x0 = int(floor(fx)), y0 = int(floor(fy));
  const float tx = fx - float(x0), ty = fy - float(y0);
  const int xa = clamp(x0, 0, int(a.width) - 1), xb = clamp(x0 + 1, 0, int(a.width) - 1);
  const int ya = clamp(y0, 0, int(a.height) - 1), yb = clamp(y0 + 1, 0, int(a.height) - 1);
  return (rgb(a.history, xa, ya) * (1.0 - tx) + rgb(a.history, xb, ya) * tx) * (1.0 - ty) +
         (rgb(a.history, xa, yb) * (1.0 - tx) + rgb(a.history, xb, yb) * tx) * ty;
}

void main() {
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= int(a.width) || y >= int(a.height)) return;
  const uint o = (uint(y) * a.width + uint(x)) * 3u;
  const vec3 c = rgb(a.current, x, y);
  Floats result = Floats(a.result);
  // The view the pixel belongs to (eyes side by side).
  const int vx = (x / int(a.viewWidth)) * int(a.viewWidth), vy = 0;
  const int vw = int(a.viewWidth), vh = int(a.viewHeight);
  const uint mi = (uint(y) * a.width + uint(x)) * 2u;
  const vec2 m = vec2(Floats(a.motion).v[mi], Floats(a.motion).v[mi + 1u]);
  const float px = float(x) + 0.5 - m.x, py = float(y) + 0.5 - m.y;
  if (a.history == 0ul || px < float(vx) || py < float(vy) || px >= float(vx + vw) ||
      py >= float(vy + vh)) {
    result.v[o] = c.x;
    result.v[o + 1u] = c.y;
    result.v[o + 2u] = c.z;
    return;
  }
  vec3 hist = max(a.catmullRom != 0u ? catmullRom(px, py) : bilinear(px, py), vec3(0.0));
  if (a.clampHistory != 0u) {
    vec3 lo = vec3(1e30), hi = vec3(-1e30);
    for (int j = -1; j <= 1; ++j)
      for (int i = -1; i <= 1; ++i) {
        const vec3 n = toYCoCg(rgb(a.current, clamp(x + i, vx, vx + vw - 1), clamp(y + j, vy, vy + vh - 1)));
        lo = min(lo, n);
        hi = max(hi, n);
      }
    hist = fromYCoCg(min(max(toYCoCg(hist), lo), hi));
  }
  const float speed = sqrt(m.x * m.x + m.y * m.y) * a.invMotionPixels;
  const float w = a.alpha + (a.motionAlpha - a.alpha) * min(speed, 1.0);
  const float wc = w / (1.0 + max(toYCoCg(c).x, 0.0));
  const float wh = (1.0 - w) / (1.0 + max(toYCoCg(hist).x, 0.0));
  const vec3 r = (c * wc + hist * wh) * (1.0 / (wc + wh));
  result.v[o] = r.x;
  result.v[o + 1u] = r.y;
  result.v[o + 2u] = r.z;
}
