#include "passes/common/gpu_filters.h"

#include <stdexcept>

#include "gpu/shaders/convolve_spv.h"
#include "gpu/shaders/dof_args.h"
#include "pipeline/gpu_frame.h"

namespace tandem {

void recordSeparableFilter(GpuFrame& gpu, uint64_t src, uint64_t dst, uint64_t temp, int w, int h,
                           int channels, const std::vector<float>& kx,
                           const std::vector<float>& ky) {
  if (kx.size() % 2 == 0 || ky.size() % 2 == 0)
    throw std::logic_error("separable filter: a kernel of even size");
  const GpuKernel& k =
      gpu.kernel("convolve", kConvolveSpv, sizeof(kConvolveSpv) / 4, sizeof(ConvolveArgs));
  GpuCommands& cmd = gpu.commands();
  const auto pass = [&](uint64_t from, uint64_t to, const std::vector<float>& weights,
                        bool horizontal) {
    ConvolveArgs a{};
    a.src = from;
    a.dst = to;
    a.weights = gpu.constants(weights.data(), weights.size() * sizeof(float));
    a.width = uint32_t(w);
    a.height = uint32_t(h);
    a.channels = uint32_t(channels);
    a.radius = uint32_t(weights.size() / 2);
    a.horizontal = horizontal ? 1 : 0;
    cmd.dispatch(k, (a.width + 7) / 8, (a.height + 7) / 8, 1, &a);
    cmd.barrier();
  };
  pass(src, temp, kx, true);
  pass(temp, dst, ky, false);
}

}  // namespace tandem
