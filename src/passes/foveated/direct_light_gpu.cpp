// direct_light on the GPU: every pixel of each view (shaders/direct_light.comp), the same lights
// in the same order as the CPU pass.
#include "gpu/shaders/direct_light_spv.h"
#include "passes/common/gpu_light_grid.h"
#include "passes/foveated/direct_light.h"
#include "passes/foveated/gpu_primary_surfaces.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"
#include "rt/diffuse_gi.h"

namespace tandem {

void DirectLightPass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  DirectLightArgs a{};
  a.scene = gpu.scene(ctx.frame).sceneAddress();
  a.views = gpuFoveatedViews(ctx);
  a.g = gpuPrimarySurfaces(ctx, *this);
  a.direct = ctx.deviceOutput(*this, Slots::ptDirect);
  const uint32_t zero[TD_FOVEATED_COUNTS] = {};
  a.counters = gpu.constants(zero, sizeof zero);
  a.lights = gpuLightGrid(gpu, nullptr, DiffuseGI::lightsSampled(*ctx.scene));
  a.count = settings().lights;
  a.viewCount = uint32_t(ctx.views.size());
  a.frameWidth = uint32_t(ctx.width);
  struct {
    uint64_t args;
    uint32_t view, pad;
  } push{gpu.constants(&a, sizeof a), 0, 0};
  const GpuKernel& k =
      gpu.kernel("direct_light", kDirectLightSpv, sizeof(kDirectLightSpv) / 4, sizeof push);
  for (size_t v = 0; v < ctx.views.size(); ++v) {
    push.view = uint32_t(v);
    gpu.dispatchInterruptibly(k, uint32_t(ctx.views[v].width() + 7) / 8,
                              uint32_t(ctx.views[v].height() + 7) / 8, &push);
  }
  const auto* counts = static_cast<const uint32_t*>(gpu.constantsData(a.counters));
  gpu.afterSubmit([&ctx, counts] { ctx.passRays += counts[TD_FOVEATED_RAYS]; });
}

}  // namespace tandem
