// What the GPU passes that trace Whitted rays (rt_whitted, rt_secondary, pt_reference) share:
// the settings as the kernels' flags, and the counters a kernel added to, reported as the CPU
// passes report them.
#pragma once
#include <cstdint>

#include "gpu/shaders/whitted_args.h"
#include "passes/common/whitted_settings.h"

namespace tandem {

// `maps`: the kernel has the frame's shadow maps (gpu_shadow_maps.h), so the shadow mode applies.
inline uint32_t gpuWhittedFlags(const WhittedSettings& w, bool maps = false) {
  return (w.texturedShadows ? TD_WHITTED_TEXTURED_SHADOWS : 0u) |
         (w.shadeAtMaxDepth ? TD_WHITTED_SHADE_AT_MAX_DEPTH : 0u) |
         (maps && w.shadows == ShadowMode::Classified ? TD_WHITTED_CLASSIFIED : 0u) |
         (maps && w.shadows == ShadowMode::Maps ? TD_WHITTED_MAPS : 0u);
}

// `counts`: the TD_COUNT_N uints a kernel added to; the shadow queries and the pass's rays.
inline void reportGpuShadows(FrameContext& ctx, const Pass& p, const uint32_t* counts,
                             double pixels) {
  ShadowCounts c;
  c.culled = counts[TD_COUNT_CULLED];
  c.traced = counts[TD_COUNT_TRACED];
  c.surfaces = counts[TD_COUNT_SURFACES];
  c.lit = counts[TD_COUNT_LIT];
  c.shadowed = counts[TD_COUNT_SHADOWED];
  reportShadows(ctx, p, c, pixels);
  ctx.passRays += double(counts[TD_COUNT_RAYS]);
}

}  // namespace tandem
