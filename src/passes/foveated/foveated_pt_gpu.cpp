// foveated_pt on the GPU: every listed pixel of both eyes in one dispatch
// (shaders/foveated_pt.comp), with the seed, light grid and samples the CPU pass takes.
#include "gpu/shaders/foveated_pt_spv.h"
#include "passes/common/gpu_light_grid.h"
#include "passes/foveated/foveated_pt.h"
#include "passes/foveated/gpu_primary_surfaces.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"
#include "rt/diffuse_gi.h"
#include "rt/sampler.h"

namespace tandem {

void FoveatedPTPass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  GpuCommands& cmd = gpu.commands();
  const ShadingContext shading = ShadingContext::from(*ctx.scene);
  const LightGrid* grid = prepare(ctx, shading);
  const Buffer& coords = ctx.input(*this, Slots::fovCoords);  // the shape (the list's length)
  FoveatedPtArgs a{};
  a.scene = gpu.scene(ctx.frame).sceneAddress();
  a.views = gpuFoveatedViews(ctx);
  a.g = gpuPrimarySurfaces(ctx, *this);
  a.coords = ctx.deviceInput(*this, Slots::fovCoords);
  a.noisy = ctx.deviceOutput(*this, Slots::ptNoisy);
  a.variance = ctx.deviceOutput(*this, Slots::ptVariance);
  // Pixels not listed stay empty (0) for the denoiser to fill.
  for (const char* slot : {Slots::ptNoisy, Slots::ptVariance}) {
    const GpuBuffer& b = gpu.read(bufferName(slot));
    cmd.fill(b, 0, b.size, 0);
  }
  cmd.barrier();
  const uint32_t zero[TD_FOVEATED_COUNTS] = {};
  a.counters = gpu.constants(zero, sizeof zero);
  a.grid = gpuLightGrid(gpu, grid, DiffuseGI::lightsSampled(*ctx.scene));
  a.listed = coords.height > 0 ? uint32_t(coords.width) : 0u;
  a.viewCount = uint32_t(ctx.views.size());
  a.frameWidth = uint32_t(ctx.width);
  const uint64_t seed = ctx.frameSeed();  // FoveatedPTPass::execute
  a.seedLo = uint32_t(seed);
  a.seedHi = uint32_t(seed >> 32);
  const uint64_t args = gpu.constants(&a, sizeof a);
  const GpuKernel& k =
      gpu.kernel("foveated_pt", kFoveatedPtSpv, sizeof(kFoveatedPtSpv) / 4, sizeof args);
  // Rows of 64 groups of 64 entries (the kernel's kRowEntries).
  const uint64_t entries = uint64_t(a.listed) * a.viewCount;
  if (entries > 0) gpu.dispatchInterruptibly(k, 64, uint32_t((entries + 4095) / 4096), &args);
  const auto* counts = static_cast<const uint32_t*>(gpu.constantsData(a.counters));
  gpu.afterSubmit([this, &ctx, counts] {
    ctx.passRays += counts[TD_FOVEATED_RAYS];
    ctx.report(*this, FoveatedPTCounters::samples, counts[TD_FOVEATED_SAMPLES]);
  });
}

}  // namespace tandem
