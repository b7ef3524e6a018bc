#version 460
// ray_mask on the GPU, one stage a dispatch, as RayMaskPass::execute (Tan et al. 2022 §3.2.1):
// inverse depth and normals (then Gaussian-filtered and, at half resolution, box-reduced), the
// 5x5 Sobel gradients (convolve.comp), eq. 2-4 with last frame's variance, at least a ray in the
// near field (and, with `dilate`, within its CoC radius of it), none where the composite's fine
// gather takes the pixel.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "dof_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { DofStagePush p; };
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Args { RayMaskArgs a; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Floats { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Counters {
  uint64_t rays, masked;
};

const float kZoneOfFocusCoc = 1.41421356;
const float kSilhouette = 0.02;

float saturate(float x) { return clamp(x, 0.0, 1.0); }

// gradients(): d / z (0 for the sky, at most 8) and the normal.
void gradientInput(RayMaskArgs a, uint x, uint y) {
  const uint i = y * a.width + x;
  Floats pos = Floats(a.position), n = Floats(a.normal), g = Floats(a.inverseDepth);
  precise const float dx = pos.v[3u * i] - a.eyeX, dy = pos.v[3u * i + 1u] - a.eyeY,
                      dz = pos.v[3u * i + 2u] - a.eyeZ;
  precise const float z = dx * a.forwardX + dy * a.forwardY + dz * a.forwardZ;
  precise const float zr = Floats(a.depth).v[i] > 0.0 ? min(a.focus / max(z, 1e-6), 8.0) : 0.0;
  g.v[4u * i] = zr;
  g.v[4u * i + 1u] = n.v[3u * i];
  g.v[4u * i + 2u] = n.v[3u * i + 1u];
  g.v[4u * i + 3u] = n.v[3u * i + 2u];
}

// downsampleBox of the blurred input (4 channels) to the mask.
void downsample(RayMaskArgs a, uint x, uint y) {
  Floats src = Floats(a.blurred), dst = Floats(a.low);
  const int w = int(a.width), h = int(a.height);
  const int xa = 2 * int(x), ya = 2 * int(y), xb = min(xa + 1, w - 1), yb = min(ya + 1, h - 1);
  const float n = float((xb - xa + 1) * (yb - ya + 1));
  for (uint c = 0u; c < 4u; ++c) {
    precise float s = src.v[4u * uint(ya * w + xa) + c];
    if (xb != xa) s += src.v[4u * uint(ya * w + xb) + c];
    if (yb != ya) s += src.v[4u * uint(yb * w + xa) + c];
    if (xb != xa && yb != ya) s += src.v[4u * uint(yb * w + xb) + c];
    dst.v[4u * (y * a.maskWidth + x) + c] = s / n;
  }
}

void nearAndFine(RayMaskArgs a, uint x, uint y) {
  Floats coc = Floats(a.coc), bokeh = Floats(a.bokeh);
  const int S = int(a.scale), W = int(a.width), H = int(a.height);
  float c = 0.0;
  bool fine = a.fineCoc > 0.0;
  for (int j = 0; j < S; ++j)
    for (int i = 0; i < S; ++i) {
      const int px = min(int(x) * S + i, W - 1), py = min(int(y) * S + j, H - 1);
      const uint k = uint(py * W + px);
      const float cp = coc.v[k];
      c = min(c, cp);
      fine = fine && abs(cp) < a.fineCoc && bokeh.v[2u * k + 1u] <= kSilhouette;
    }
  Floats nf = Floats(a.nearFine);
  const uint o = 2u * (y * a.maskWidth + x);
  nf.v[o] = c < -kZoneOfFocusCoc ? -0.5 * c / float(S) : 0.0;
  nf.v[o + 1u] = fine ? 1.0 : 0.0;
}

void tileMax(RayMaskArgs a, uint tx, uint ty) {
  Floats nf = Floats(a.nearFine);
  float m = 0.0;
  const uint y1 = min((ty + 1u) * TD_MASK_TILE, a.maskHeight);
  const uint x1 = min((tx + 1u) * TD_MASK_TILE, a.maskWidth);
  for (uint y = ty * TD_MASK_TILE; y < y1; ++y)
    for (uint x = tx * TD_MASK_TILE; x < x1; ++x) m = max(m, nf.v[2u * (y * a.maskWidth + x)]);
  Floats(a.tileMax).v[ty * a.tilesX + tx] = m;
}

void neighbourMax(RayMaskArgs a, uint tx, uint ty) {
  Floats t = Floats(a.tileMax);
  float m = 0.0;
  const int X = int(a.tilesX), Y = int(a.tilesY);
  for (int j = max(int(ty) - 1, 0); j <= min(int(ty) + 1, Y - 1); ++j)
    for (int i = max(int(tx) - 1, 0); i <= min(int(tx) + 1, X - 1); ++i)
      m = max(m, t.v[uint(j * X + i)]);
  Floats(a.tileNear).v[ty * a.tilesX + tx] = m;
}

// NearDilation::nearAt: a near-field pixel within the neighbourhood's largest near radius.
bool nearAround(RayMaskArgs a, int x, int y) {
  const int w = int(a.maskWidth), h = int(a.maskHeight);
  const int r = int(ceil(Floats(a.tileNear).v[uint(y / int(TD_MASK_TILE)) * a.tilesX +
                                              uint(x / int(TD_MASK_TILE))]));
  if (r <= 0) return false;
  Floats nf = Floats(a.nearFine);
  for (int j = max(y - r, 0); j < min(y + r + 1, h); ++j)
    for (int i = max(x - r, 0); i < min(x + r + 1, w); ++i)
      if (nf.v[2u * uint(j * w + i)] > 0.0) return true;
  return false;
}

// std::round of a value >= 0: halves away from zero (v - trunc(v) is exact, unlike v + 0.5).
float roundHalfUp(float v) {
  const float t = trunc(v);
  return v - t >= 0.5 ? t + 1.0 : t;
}

void rays(RayMaskArgs a, uint x, uint y) {
  const uint i = y * a.maskWidth + x;
  Floats gx = Floats(a.gx), gy = Floats(a.gy);
  precise const float dd = sqrt(gx.v[4u * i] * gx.v[4u * i] + gy.v[4u * i] * gy.v[4u * i]) / 48.0;
  precise float nn = 0.0;
  for (uint c = 1u; c < 4u; ++c) nn += gx.v[4u * i + c] * gx.v[4u * i + c] + gy.v[4u * i + c] * gy.v[4u * i + c];
  precise const float xe = (dd + sqrt(nn) / 48.0) * a.s;    // eq. 2
  precise const float xn = saturate(1.0 - 1.0 / (xe + 1.0));  // eq. 3
  const float var = a.variance != 0ul ? Floats(a.variance).v[i] : 0.0;
  precise const float share = saturate(xn + var * a.varianceWeight);
  float r = roundHalfUp(share * a.m);  // eq. 4
  Floats nf = Floats(a.nearFine);
  bool near = nf.v[2u * i] > 0.0;
  if (!near && a.dilate != 0u) near = nearAround(a, int(x), int(y));
  if (near && a.m > 0.0) r = max(r, 1.0);
  const float rays = nf.v[2u * i + 1u] > 0.5 ? 0.0 : r;
  Floats(a.mask).v[i] = rays;
  if (rays > 0.0) {
    atomicAdd(Counters(a.counters).rays, uint64_t(rays));
    atomicAdd(Counters(a.counters).masked, 1ul);
  }
}

void main() {
  const RayMaskArgs a = Args(p.args).a;
  const uint x = gl_GlobalInvocationID.x, y = gl_GlobalInvocationID.y;
  if (p.stage == TD_MASK_INPUT) {
    if (x < a.width && y < a.height) gradientInput(a, x, y);
  } else if (p.stage == TD_MASK_TILE_MAX || p.stage == TD_MASK_NEIGHBOUR_MAX) {
    if (x >= a.tilesX || y >= a.tilesY) return;
    if (p.stage == TD_MASK_TILE_MAX)
      tileMax(a, x, y);
    else
      neighbourMax(a, x, y);
  } else if (x < a.maskWidth && y < a.maskHeight) {
    if (p.stage == TD_MASK_DOWNSAMPLE)
      downsample(a, x, y);
    else if (p.stage == TD_MASK_NEAR)
      nearAndFine(a, x, y);
    else
      rays(a, x, y);
  }
}
