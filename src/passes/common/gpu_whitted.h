// What the GPU passes that trace Whitted rays (rt_whitted, rt_secondary, pt_reference) share:
// the settings as the kernels' flags, and the counters a kernel added to, reported as the CPU
// passes report them.
#pragma once
#include <cstdint>

#include "gpu/shaders/whitted_args.h"
#include "passes/common/whitted_settings.h"

namespace tandem {

inline uint32_t gpuWhittedFlags(const WhittedSettings& w) {
  return (w.texturedShadows ? TD_WHITTED_TEXTURED_SHADOWS : 0u) |
         (w.shadeAtMaxDepth ? TD_WHITTED_SHADE_AT_MAX_DEPTH : 0u);
}

// `counts`: the TD_COUNT_N uints a kernel added to; the shadow queries and the pass's rays.
inline void reportGpuShadows(FrameContext& ctx, const Pass& p, const uint32_t* counts,
                             double pixels) {
  ShadowCounts c;
  c.culled = counts[TD_COUNT_CULLED];
  c.traced = counts[TD_COUNT_TRACED];
  c.surfaces = counts[TD_COUNT_SURFACES];
  reportShadows(ctx, p, c, pixels);
  ctx.passRays += double(counts[TD_COUNT_RAYS]);
}

}  // namespace tandem
