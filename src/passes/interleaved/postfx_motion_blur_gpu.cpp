// postfx_motion_blur and mb_composite on the GPU (shaders/postfx_motion_blur.comp): each view's
// tiles, neighbourhoods and gather as the CPU computes them.
#include <algorithm>
#include <vector>

#include "gpu/shaders/motion_blur_args.h"
#include "gpu/shaders/postfx_motion_blur_spv.h"
#include "passes/interleaved/mb_composite.h"
#include "passes/interleaved/postfx_motion_blur.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"

namespace tandem {

namespace {

const GpuKernel& motionBlurKernel(GpuFrame& gpu) {
  return gpu.kernel("postfx_motion_blur", kPostfxMotionBlurSpv, sizeof(kPostfxMotionBlurSpv) / 4,
                    sizeof(uint64_t) + sizeof(uint32_t));
}

struct StagePush {
  uint64_t args;
  uint32_t stage, pad;
};

}  // namespace

void PostfxMotionBlurPass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  GpuCommands& cmd = gpu.commands();
  const PostfxMotionBlurSettings& s = settings();
  MotionBlurArgs a{};
  a.colour = ctx.deviceInput(*this, Slots::hdr);
  a.velocity = ctx.deviceInput(*this, Slots::velocity);
  a.depth = ctx.deviceInput(*this, Slots::viewDepth);
  a.postfx = ctx.deviceOutput(*this, Slots::mbPostfx);
  a.mask = ctx.deviceOutput(*this, Slots::mbMask);
  const uint32_t zero = 0;
  a.masked = gpu.constants(&zero, sizeof zero);
  a.frameWidth = uint32_t(ctx.width);
  a.frameHeight = uint32_t(ctx.height);
  a.K = s.tileSize;
  a.S = s.samples | 1;
  a.softZ = s.softZ;
  a.threshold = s.maskThreshold;
  a.edgesOnly = s.mask == PostfxMotionBlurSettings::Mask::Edges ? 1u : 0u;
  // Each view's tiles in turn (the views' blurs are independent: one tile buffer serves all).
  size_t tiles = 0, most = 0;
  for (const View& v : ctx.views) {
    const size_t n = size_t((v.width() + a.K - 1) / a.K) * size_t((v.height() + a.K - 1) / a.K);
    tiles += n;
    most = std::max(most, n);
  }
  a.tiles = gpu.scratch(name() + ":tiles", most * TD_MB_TILE_FLOATS * sizeof(float)).address;
  const GpuKernel& k = motionBlurKernel(gpu);
  for (const View& v : ctx.views) {
    a.ox = v.x, a.oy = v.y, a.width = v.width(), a.height = v.height();
    a.tilesX = (a.width + a.K - 1) / a.K;
    a.tilesY = (a.height + a.K - 1) / a.K;
    StagePush push{gpu.constants(&a, sizeof a), TD_MB_TILES, 0};
    const uint32_t tx = uint32_t(a.tilesX + 7) / 8, ty = uint32_t(a.tilesY + 7) / 8;
    cmd.dispatch(k, tx, ty, 1, &push);
    cmd.barrier();
    push.stage = TD_MB_NEIGHBOURS;
    cmd.dispatch(k, tx, ty, 1, &push);
    cmd.barrier();
    push.stage = TD_MB_GATHER;
    cmd.dispatch(k, uint32_t(a.width + 7) / 8, uint32_t(a.height + 7) / 8, 1, &push);
    cmd.barrier();  // the next view's tiles overwrite these
  }
  const auto* masked = static_cast<const uint32_t*>(gpu.constantsData(a.masked));
  gpu.afterSubmit([this, &ctx, masked, tiles] {
    ctx.report(*this, PostfxMotionBlurCounters::maskedTilesPercent,
               tiles ? 100.0 * double(*masked) / double(tiles) : 0.0);
  });
}

void MotionBlurCompositePass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  MotionBlurArgs a{};
  a.postfx = ctx.deviceInput(*this, Slots::mbPostfx);
  a.interleaved = ctx.deviceInput(*this, Slots::mbInterleaved);
  a.mask = ctx.deviceInput(*this, Slots::mbMask);
  a.composite = ctx.deviceOutput(*this, Slots::hdr);
  a.frameWidth = uint32_t(ctx.width);
  a.frameHeight = uint32_t(ctx.height);
  StagePush push{gpu.constants(&a, sizeof a), TD_MB_COMPOSITE, 0};
  gpu.commands().dispatch(motionBlurKernel(gpu), uint32_t(ctx.width + 7) / 8,
                          uint32_t(ctx.height + 7) / 8, 1, &push);
}

}  // namespace tandem
