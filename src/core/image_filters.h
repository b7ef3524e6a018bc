// Image filters shared by passes (DoF, TAA, denoisers, reconstruction): Gaussian blur, 5x5 Sobel,
// 3x3 median, down/upsampling (box, bilinear, depth-aware), mip chains, and bilinear / Catmull-Rom
// sampling. Every filter works on every channel of an interleaved Buffer, with clamp-to-edge
// borders; separable filters run row by row over the flat float array (one contiguous inner
// loop the compiler vectorises), and rows are spread over threads.
#pragma once
#include <vector>

#include "core/buffer.h"

namespace tandem {

// Separable Gaussian of standard deviation `sigma` pixels (radius ceil(3 sigma), weights
// normalised). sigma <= 0 returns a copy.
Buffer gaussianBlur(const Buffer& in, float sigma);
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
// Catmull-Rom (bicubic, 4x4 taps) sample; sharper than bilinear for reprojection (TAA).
void sampleCatmullRom(const Buffer& b, float x, float y, float* out);

}  // namespace tandem
