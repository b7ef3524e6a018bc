// Image filters shared by passes (DoF, TAA, denoisers, reconstruction): Gaussian blur, 5x5 Sobel,
// 3x3 median, down/upsampling (box, bilinear, depth-aware), mip chains, and bilinear / Catmull-Rom
// sampling. Every filter works on every channel of an interleaved Buffer, with clamp-to-edge
// borders; separable filters run row by row over the flat float array (one contiguous inner
// loop the compiler vectorises), and rows are spread over threads.
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/buffer.h"

namespace tandem {

// Separable Gaussian of standard deviation `sigma` pixels (radius ceil(3 sigma), weights
// normalised). sigma <= 0 returns a copy.
Buffer gaussianBlur(const Buffer& in, float sigma);
// gaussianBlur's normalised 1-D kernel (radius ceil(3 sigma)); empty when sigma <= 0 (no blur).
std::vector<float> gaussianKernel(float sigma);
// Convolution with a separable kernel: `kx` along rows, then `ky` along columns (odd lengths,
// centred, not normalised here).
Buffer separableFilter(const Buffer& in, const std::vector<float>& kx,
                       const std::vector<float>& ky);
// 5x5 Sobel gradient of channel `channel`: 2 channels (d/dx, d/dy), x to the right, y down;
// kernels smooth (1 4 6 4 1) x derive (-1 -2 0 2 1), unnormalised (a unit-slope ramp gives 128).
Buffer sobel5x5(const Buffer& in, int channel = 0);
// Per-channel median of each 3x3 neighbourhood.
Buffer median3x3(const Buffer& in);

// Half size (rounded up): mean of each 2x2 block (a block cut by an odd edge averages what it has).
Buffer downsampleBox(const Buffer& in);
// Any size: bilinear samples at the output pixel centres mapped into the input.
Buffer resizeBilinear(const Buffer& in, int width, int height);
// Upsamples `low` to `highDepth`'s size, weighting the 4 bilinear neighbours by how close their
// depth (`lowDepth`, same size as `low`) is to the full-resolution depth: edges of the depth
// buffer are not blurred across (joint bilateral upsampling, Kopf et al. 2007). `depthScale`
// sets how fast the weight falls with the depth difference.
Buffer upsampleDepthAware(const Buffer& low, const Buffer& lowDepth, const Buffer& highDepth,
                          float depthScale = 100.0f);
// Level 0 is `in`; each next level is downsampleBox of the last, down to 1 x 1.
std::vector<Buffer> mipChain(const Buffer& in);

// Bilinear sample at continuous pixel coordinates (pixel centres at +0.5), clamp to edge; writes
// `channels` values to out.
void sampleBilinear(const Buffer& b, float x, float y, float* out);
// sampleBilinear for a buffer of exactly N channels, inline (per-pixel gathers of a few taps).
template <int N>
inline void sampleBilinearN(const Buffer& b, float x, float y, float* out) {
  // Below -1 every tap clamps to the first texel anyway; from -1 on, truncation of fx + 1 is the
  // floor (std::floor is a library call without SSE4.1).
  const float fx = std::max(x - 0.5f, -1.0f), fy = std::max(y - 0.5f, -1.0f);
  const int x0 = int(fx + 1.0f) - 1, y0 = int(fy + 1.0f) - 1;
  const float tx = fx - float(x0), ty = fy - float(y0);
  const int xa = std::clamp(x0, 0, b.width - 1), xb = std::clamp(x0 + 1, 0, b.width - 1);
  const int ya = std::clamp(y0, 0, b.height - 1), yb = std::clamp(y0 + 1, 0, b.height - 1);
  const float *p00 = b.at(xa, ya), *p10 = b.at(xb, ya), *p01 = b.at(xa, yb), *p11 = b.at(xb, yb);
  for (int c = 0; c < N; ++c)
    out[c] = (p00[c] * (1 - tx) + p10[c] * tx) * (1 - ty) + (p01[c] * (1 - tx) + p11[c] * tx) * ty;
}

// Catmull-Rom (bicubic, 4x4 taps) sample; sharper than bilinear for reprojection (TAA).
void sampleCatmullRom(const Buffer& b, float x, float y, float* out);

// The 1-D Catmull-Rom weights of the four taps around a fractional position t in [0, 1).
inline void catmullRomWeights(float t, float w[4]) {
  w[0] = t * (-0.5f + t * (1.0f - 0.5f * t));
  w[1] = 1.0f + t * t * (-2.5f + 1.5f * t);
  w[2] = t * (0.5f + t * (2.0f - 1.5f * t));
  w[3] = t * t * (-0.5f + 0.5f * t);
}

// sampleCatmullRom of a 3-channel buffer where all 16 taps lie inside (the common case, inlined
// for per-pixel use); returns false near the border, where the caller uses sampleCatmullRom.
inline bool sampleCatmullRomRgbInside(const Buffer& b, float x, float y, float out[3]) {
  const float fx = x - 0.5f, fy = y - 0.5f;
  const int x1 = int(std::floor(fx)), y1 = int(std::floor(fy));
  if (x1 < 1 || y1 < 1 || x1 + 2 >= b.width || y1 + 2 >= b.height) return false;
  float wx[4], wy[4];
  catmullRomWeights(fx - float(x1), wx);
  catmullRomWeights(fy - float(y1), wy);
  float r = 0, g = 0, bl = 0;
  for (int j = 0; j < 4; ++j) {
    const float* row = &b.data[(size_t(y1 - 1 + j) * size_t(b.width) + size_t(x1 - 1)) * 3];
    const float rr = wx[0] * row[0] + wx[1] * row[3] + wx[2] * row[6] + wx[3] * row[9];
    const float gg = wx[0] * row[1] + wx[1] * row[4] + wx[2] * row[7] + wx[3] * row[10];
    const float bb = wx[0] * row[2] + wx[1] * row[5] + wx[2] * row[8] + wx[3] * row[11];
    r += wy[j] * rr;
    g += wy[j] * gg;
    bl += wy[j] * bb;
  }
  out[0] = r;
  out[1] = g;
  out[2] = bl;
  return true;
}

}  // namespace tandem
