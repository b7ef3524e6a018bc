#version 460
// dof_reconstruction on the GPU, one stage a dispatch, as DofReconstructionPass::execute (Tan et
// al. 2022 §3.2.4): the 3x3 median of every channel, mip levels 0..3 premultiplied by coverage,
// then per pixel the circular gather (eq. 8's level, taps rejected where their blur does not reach
// the centre) lerped in by eq. 5's b.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "dof_args.h"
#include "image_filters.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { DofStagePush p; };
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Args {
  DofReconstructionArgs a;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Floats { float v[]; };

const uint N = TD_COMPOSITE_RT_CHANNELS;  // dof::RtChannels: coc 3, coverage 5
const uint kCoc = 3u, kCov = 5u;


void median(DofReconstructionArgs a, uint x, uint y) {
  Floats in_ = Floats(a.rtColor), filtered = Floats(a.filtered);
  const int W = int(a.width), H = int(a.height);
  for (uint c = 0u; c < N; ++c) {
    float v[9];
    int n = 0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int sx = clamp(int(x) + dx, 0, W - 1), sy = clamp(int(y) + dy, 0, H - 1);
        v[n++] = in_.v[N * uint(sy * W + sx) + c];
      }
    filtered.v[N * (y * a.width + x) + c] = median9(v);
  }
}

void premultiply(DofReconstructionArgs a, uint x, uint y) {
  Floats f = Floats(a.filtered), m = Floats(a.mips[0]);
  const uint o = N * (y * a.width + x);
  const float cov = f.v[o + kCov];
  for (uint c = 0u; c < N; ++c) m.v[o + c] = c == kCov ? cov : f.v[o + c] * cov;
}

// downsampleBox: the mean of each 2x2 block (what an odd edge leaves of it).
void downsample(DofReconstructionArgs a, uint x, uint y) {
  Floats src = Floats(a.src), dst = Floats(a.dst);
  const int w = int(a.srcWidth), h = int(a.srcHeight);
  const int xa = 2 * int(x), ya = 2 * int(y), xb = min(xa + 1, w - 1), yb = min(ya + 1, h - 1);
  const float n = float((xb - xa + 1) * (yb - ya + 1));
  for (uint c = 0u; c < N; ++c) {
    precise float s = src.v[N * uint(ya * w + xa) + c];
    if (xb != xa) s += src.v[N * uint(ya * w + xb) + c];
    if (yb != ya) s += src.v[N * uint(yb * w + xa) + c];
    if (xb != xa && yb != ya) s += src.v[N * uint(yb * w + xb) + c];
    dst.v[N * (y * a.dstWidth + x) + c] = s / n;
  }
}

// sampleBilinearN<9> of mip level `level` at (x, y).
void bilinear9(DofReconstructionArgs a, uint level, float x, float y, out float s[9]) {
  Floats mip = Floats(a.mips[level]);
  const int w = a.mipWidth[level], h = a.mipHeight[level];
  precise const float fx = max(x - 0.5, -1.0), fy = max(y - 0.5, -1.0);
  const int x0 = int(fx + 1.0) - 1, y0 = int(fy + 1.0) - 1;
  precise const float tx = fx - float(x0), ty = fy - float(y0);
  const int xa = clamp(x0, 0, w - 1), xb = clamp(x0 + 1, 0, w - 1);
  const int ya = clamp(y0, 0, h - 1), yb = clamp(y0 + 1, 0, h - 1);
  for (uint c = 0u; c < N; ++c) {
    const float p00 = mip.v[N * uint(ya * w + xa) + c], p10 = mip.v[N * uint(ya * w + xb) + c];
    const float p01 = mip.v[N * uint(yb * w + xa) + c], p11 = mip.v[N * uint(yb * w + xb) + c];
    precise const float r =
        (p00 * (1.0 - tx) + p10 * tx) * (1.0 - ty) + (p01 * (1.0 - tx) + p11 * tx) * ty;
    s[c] = r;
  }
}

void gather(DofReconstructionArgs a, uint x, uint y) {
  Floats f = Floats(a.filtered), out_ = Floats(a.rtRecon), taps = Floats(a.taps);
  const uint o = N * (y * a.width + x);
  float c0[9];
  for (uint c = 0u; c < N; ++c) c0[c] = f.v[o + c];
  float result[9] = c0;
  precise const float b = clamp(Floats(a.variance).v[y * a.width + x] * a.varianceWeight, 0.0, 0.9);
  precise const float radius = 0.5 * c0[kCoc] / a.scale;  // this resolution's pixels
  // Below 1/256 the lerp cannot change an 8-bit value by a step: no gather (as on the CPU).
  if (c0[kCov] > 0.0 && b >= 1.0 / 256.0 && radius >= 0.5) {
    precise const float lod = clamp(c0[kCoc] * a.lodScale, 0.0, float(a.levels - 1u));  // eq. 8
    const uint level = uint(int(lod));
    const float ms = float(a.mipWidth[level]) / float(a.width);
    precise float acc[9] = float[9](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for (uint t = 0u; t < TD_RECON_TAPS; ++t) {
      const float ring = taps.v[3u * t];
      precise const float r = radius * ring / 2.0;
      precise const float sx = float(x) + 0.5 + r * taps.v[3u * t + 1u];
      precise const float sy = float(y) + 0.5 + r * taps.v[3u * t + 2u];
      float s[9];
      bilinear9(a, level, sx * ms, sy * ms, s);
      if (s[kCov] <= 1e-4) continue;
      // A tap whose own blur does not reach the centre.
      if (ring > 0.0 && 0.5 * s[kCoc] < r * a.scale * s[kCov]) continue;
      for (uint c = 0u; c < N; ++c) acc[c] += s[c];
    }
    if (acc[kCov] > 1e-4) {
      precise const float inv = 1.0 / acc[kCov];
      for (uint c = 0u; c < N; ++c)
        if (c != kCov) {
          precise const float v = c0[c] + (acc[c] * inv - c0[c]) * b;
          result[c] = v;
        }
    }
  }
  for (uint c = 0u; c < N; ++c) out_.v[o + c] = result[c];
}

void main() {
  const DofReconstructionArgs a = Args(p.args).a;
  const uint x = gl_GlobalInvocationID.x, y = gl_GlobalInvocationID.y;
  if (p.stage == TD_RECON_DOWNSAMPLE) {
    if (x < a.dstWidth && y < a.dstHeight) downsample(a, x, y);
    return;
  }
  if (x >= a.width || y >= a.height) return;
  if (p.stage == TD_RECON_MEDIAN)
    median(a, x, y);
  else if (p.stage == TD_RECON_PREMULTIPLY)
    premultiply(a, x, y);
  else
    gather(a, x, y);
}
