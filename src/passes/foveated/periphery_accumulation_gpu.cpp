// periphery_accumulation on the GPU: every pixel of each view in one dispatch
// (shaders/periphery_accumulation.comp); the history stays on the device between frames.
#include <cmath>
#include <vector>

#include "gpu/shaders/foveated_args.h"
#include "gpu/shaders/periphery_accumulation_spv.h"
#include "passes/foveated/gpu_primary_surfaces.h"
#include "passes/foveated/periphery_accumulation.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"

namespace tandem {

void PeripheryAccumulationPass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  const PeripheryAccumulationSettings& s = settings();
  PeripheryArgs a{};
  a.views = gpuEyeViews(ctx);
  a.noisy = ctx.deviceInput(*this, Slots::ptNoisy);
  a.mask = ctx.deviceInput(*this, Slots::fovMask);
  a.layer = ctx.deviceInput(*this, Slots::fovLayer);
  a.motion = ctx.deviceInput(*this, Slots::motion);
  a.position = ctx.deviceInput(*this, Slots::position);
  a.normal = ctx.deviceInput(*this, Slots::normal);
  a.depth = ctx.deviceInput(*this, Slots::depth);
  a.diffuse = ctx.deviceInput(*this, Slots::diffuse);
  a.emission = ctx.deviceInput(*this, Slots::emission);
  a.variance =
      ctx.optionalInput(*this, Slots::ptVariance) ? ctx.deviceInput(*this, Slots::ptVariance) : 0;
  a.previous = ctx.devicePrevious(*this, Slots::ptHistory);
  a.accum = ctx.deviceOutput(*this, Slots::ptAccum);
  a.accumVariance = ctx.deviceOutput(*this, Slots::ptAccumVariance);
  a.accumMask = ctx.deviceOutput(*this, Slots::ptAccumMask);
  a.history = ctx.deviceOutput(*this, Slots::ptHistory);
  const PeripheryCounters zero{};
  a.counters = gpu.constants(&zero, sizeof zero);
  a.width = uint32_t(ctx.width);
  a.viewCount = uint32_t(ctx.views.size());
  a.flags =
      (s.demodulate ? TD_PERIPHERY_DEMODULATE : 0u) | (s.fillUnlisted ? TD_PERIPHERY_FILL : 0u);
  a.fromLayer = s.fromLayer;
  a.alphaMin = s.alphaMin;
  a.positionTolerance = s.positionTolerance;
  a.minCos = std::cos(s.normalTolerance * kPi / 180.0f);
  const uint64_t args = gpu.constants(&a, sizeof a);
  const GpuKernel& k = gpu.kernel("periphery_accumulation", kPeripheryAccumulationSpv,
                                  sizeof(kPeripheryAccumulationSpv) / 4, sizeof args);
  gpu.commands().dispatch(k, uint32_t(ctx.width + 7) / 8, uint32_t(ctx.height + 7) / 8, 1, &args);
  const auto* counts = static_cast<const PeripheryCounters*>(gpu.constantsData(a.counters));
  gpu.afterSubmit([this, &ctx, counts] {
    const double pixels = double(counts->pixels);
    ctx.report(*this, PeripheryAccumulationCounters::meanFrames,
               pixels > 0 ? double(counts->framesSum) / 65536.0 / pixels : 0.0);
  });
}

}  // namespace tandem
