// Image filters recorded on the GPU as core/image_filters.h computes them on the CPU
// (convolve.comp: the same taps in the same order), for the passes that filter device buffers.
#pragma once
#include <cstdint>
#include <vector>

namespace tandem {

class GpuFrame;

// separableFilter of the w x h, `channels`-channel device buffer at `src` into `dst`: rows with
// kx, then columns with ky (odd sizes, centred), through `temp` (as large as src). Barriers after
// each pass, so what follows reads dst.
void recordSeparableFilter(GpuFrame& gpu, uint64_t src, uint64_t dst, uint64_t temp, int w, int h,
                           int channels, const std::vector<float>& kx,
                           const std::vector<float>& ky);

}  // namespace tandem
