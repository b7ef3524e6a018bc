#version 460
// postfx_motion_blur on the GPU (McGuire, Hennessy, Bukowski & Osman 2012), one stage a
// dispatch, what PostfxMotionBlurPass::execute computes for a view: TileMax (an invocation a
// tile), NeighborMax and the mask of mixed motion (an invocation a tile), the gather along the
// neighbourhood's largest velocity with the same per-pixel jitter (an invocation a pixel); and
// mb_composite's blend of the post-process and the interleaved image by the mask.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "motion_blur_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push {
  uint64_t args;
  uint stage;
};
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ArgsRef {
  MotionBlurArgs a;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Floats { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Uints { uint v[]; };

MotionBlurArgs A;

// Blur radius at view pixel (x, y): half the displacement over the shutter, at most K.
vec2 radiusAt(int x, int y) {
  const uint i = uint(y + A.oy) * A.frameWidth + uint(x + A.ox);
  Floats v = Floats(A.velocity);
  vec2 r = vec2(0.5 * v.v[2u * i], 0.5 * v.v[2u * i + 1u]);
  const float l = length(r);
  if (l > float(A.K)) r = r * (float(A.K) / l);
  return r;
}
float depthAt(int x, int y) {
  return Floats(A.depth).v[uint(y + A.oy) * A.frameWidth + uint(x + A.ox)];
}
vec3 colourAt(int x, int y) {
  Floats c = Floats(A.colour);
  const uint i = 3u * (uint(y + A.oy) * A.frameWidth + uint(x + A.ox));
  return vec3(c.v[i], c.v[i + 1u], c.v[i + 2u]);
}
uint tileAt(int tx, int ty) { return uint(ty * A.tilesX + tx) * uint(TD_MB_TILE_FLOATS); }

void tiles(int tx, int ty) {
  vec2 best = vec2(0.0);
  float bestL = -1.0, minL = 1e30;
  bool edge = false;
  for (int y = ty * A.K; y < min(A.height, ty * A.K + A.K); ++y)
    for (int x = tx * A.K; x < min(A.width, tx * A.K + A.K); ++x) {
      const vec2 r = radiusAt(x, y);
      const float l = length(r);
      if (l > bestL) bestL = l, best = r;
      minL = min(minL, l);
      if (A.edgesOnly != 0u && ((x + 1 < A.width && length(radiusAt(x + 1, y) - r) > A.threshold) ||
                                (y + 1 < A.height && length(radiusAt(x, y + 1) - r) > A.threshold)))
        edge = true;
    }
  Floats t = Floats(A.tiles);
  const uint at = tileAt(tx, ty);
  t.v[at] = best.x, t.v[at + 1u] = best.y, t.v[at + 2u] = minL, t.v[at + 3u] = edge ? 1.0 : 0.0;
}

vec2 tileMax(int tx, int ty) {
  Floats t = Floats(A.tiles);
  const uint at = tileAt(tx, ty);
  return vec2(t.v[at], t.v[at + 1u]);
}

void neighbours(int tx, int ty) {
  Floats t = Floats(A.tiles);
  vec2 best = vec2(0.0);
  float bestL = -1.0, minL = 1e30;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int x = tx + dx, y = ty + dy;
      if (x < 0 || y < 0 || x >= A.tilesX || y >= A.tilesY) continue;
      const vec2 r = tileMax(x, y);
      if (length(r) > bestL) bestL = length(r), best = r;
      minL = min(minL, t.v[tileAt(x, y) + 2u]);
    }
  float spread = bestL - minL;
  bool edge = false;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int x = tx + dx, y = ty + dy;
      if (x < 0 || y < 0 || x >= A.tilesX || y >= A.tilesY) continue;
      spread = max(spread, length(tileMax(x, y) - best));
      edge = edge || t.v[tileAt(x, y) + 3u] != 0.0;
    }
  const bool mixed = A.edgesOnly != 0u ? edge : spread > A.threshold;
  const uint at = tileAt(tx, ty);
  t.v[at + 4u] = best.x, t.v[at + 5u] = best.y;
  t.v[at + 6u] = bestL > 0.5 && mixed ? 1.0 : 0.0;
  if (bestL > 0.5 && mixed) atomicAdd(Uints(A.masked).v[0], 1u);
}

float tileMask(int tx, int ty) {
  tx = clamp(tx, 0, A.tilesX - 1);
  ty = clamp(ty, 0, A.tilesY - 1);
  return Floats(A.tiles).v[tileAt(tx, ty) + 6u];
}
// The mask: tile values bilinearly between tile centres, 1 wherever a masked tile is.
float maskAt(int x, int y) {
  const float fx = (float(x) + 0.5) / float(A.K) - 0.5, fy = (float(y) + 0.5) / float(A.K) - 0.5;
  const int ix = int(floor(fx)), iy = int(floor(fy));
  const float ax = fx - float(ix), ay = fy - float(iy);
  float m = (1.0 - ay) * ((1.0 - ax) * tileMask(ix, iy) + ax * tileMask(ix + 1, iy)) +
            ay * ((1.0 - ax) * tileMask(ix, iy + 1) + ax * tileMask(ix + 1, iy + 1));
  if (tileMask(x / A.K, y / A.K) > 0.0) m = 1.0;
  return m;
}

float cone(float dist, float speed) {
  return speed <= 0.0 ? 0.0 : clamp(1.0 - dist / speed, 0.0, 1.0);
}
float smoothStep(float a, float b, float x) {  // the CPU's, written out
  const float t = clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}
float cylinder(float dist, float speed) {
  if (speed <= 0.0) return dist <= 0.0 ? 1.0 : 0.0;  // a still pixel covers only itself
  return 1.0 - smoothStep(0.95 * speed, 1.05 * speed, dist);
}
float softFront(float a, float b, float extent) { return clamp(1.0 - (a - b) / extent, 0.0, 1.0); }
int roundAway(float x) {  // std::lround: halves away from zero (x - trunc(x) is exact)
  const float t = trunc(x);
  return int(t) + (abs(x - t) >= 0.5 ? int(sign(x)) : 0);
}

vec3 gather(int x, int y, vec3 cx, vec2 vn) {
  const vec2 vx = radiusAt(x, y);
  const float sx = max(length(vx), 0.5), zx = depthAt(x, y);
  float weight = 1.0 / sx;
  vec3 sum = cx * weight;
  // Per-pixel jitter in [-0.5, 0.5] (the CPU's hash).
  uint h = uint(x) * 73856093u ^ uint(y) * 19349663u;
  h = (h ^ (h >> 13)) * 0x5bd1e995u;
  const float j = float(h >> 8) / float(1 << 24) - 0.5;
  for (int i = 0; i < A.S; ++i) {
    if (i == (A.S - 1) / 2) continue;
    const float t = -1.0 + 2.0 * (float(i) + j + 1.0) / float(A.S + 1);
    const int yx = clamp(roundAway(float(x) + vn.x * t), 0, A.width - 1);
    const int yy = clamp(roundAway(float(y) + vn.y * t), 0, A.height - 1);
    const float dist = sqrt(float((yx - x) * (yx - x) + (yy - y) * (yy - y)));
    const vec2 vy = radiusAt(yx, yy);
    const float sy = length(vy), zy = depthAt(yx, yy);
    const float f = softFront(zy, zx, A.softZ), b = softFront(zx, zy, A.softZ);
    const float a =
        f * cone(dist, sy) + b * cone(dist, sx) + cylinder(dist, sy) * cylinder(dist, sx) * 2.0;
    weight += a;
    sum = sum + colourAt(yx, yy) * a;
  }
  return sum * (1.0 / weight);
}

void pixel(int x, int y) {
  const uint i = uint(y + A.oy) * A.frameWidth + uint(x + A.ox);
  Floats(A.mask).v[i] = maskAt(x, y);
  Floats t = Floats(A.tiles);
  const uint at = tileAt(x / A.K, y / A.K);
  const vec2 vn = vec2(t.v[at + 4u], t.v[at + 5u]);
  const vec3 cx = colourAt(x, y);
  const vec3 c = length(vn) <= 0.5 ? cx : gather(x, y, cx, vn);
  Floats out3 = Floats(A.postfx);
  out3.v[3u * i] = c.x, out3.v[3u * i + 1u] = c.y, out3.v[3u * i + 2u] = c.z;
}

// mb_composite: the post-process where the mask is 0, the interleaved samples where it is 1.
void composite(int x, int y) {
  const uint i = uint(y) * A.frameWidth + uint(x);
  const float m = clamp(Floats(A.mask).v[i], 0.0, 1.0);
  Floats p = Floats(A.postfx), s = Floats(A.interleaved), o = Floats(A.composite);
  for (uint k = 0u; k < 3u; ++k) o.v[3u * i + k] = p.v[3u * i + k] * (1.0 - m) + s.v[3u * i + k] * m;
}

void main() {
  A = ArgsRef(args).a;
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (stage == TD_MB_COMPOSITE) {
    if (x < int(A.frameWidth) && y < int(A.frameHeight)) composite(x, y);
  } else if (stage == TD_MB_GATHER) {
    if (x < A.width && y < A.height) pixel(x, y);
  } else if (x < A.tilesX && y < A.tilesY) {
    if (stage == TD_MB_TILES)
      tiles(x, y);
    else
      neighbours(x, y);
  }
}
