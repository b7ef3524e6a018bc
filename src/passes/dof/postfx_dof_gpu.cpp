// postfx_dof on the GPU: PostfxDofPass's five steps as the stages of shaders/postfx_dof.comp, over
// half-resolution scratch of the pass's own, with the taps the CPU takes (dof::gatherTaps).
#include <vector>

#include "gpu/shaders/dof_args.h"
#include "gpu/shaders/postfx_dof_spv.h"
#include "passes/dof/gather_taps.h"
#include "passes/dof/postfx_dof.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"

namespace tandem {

void PostfxDofPass::executeGpu(FrameContext& ctx) {
  static_assert(TD_POSTFX_TILE == dof::kPostfxTile && TD_POSTFX_TAPS == dof::kGatherTaps &&
                TD_TAP_FLOATS == 5 && dof::BokehChannels::kCount == 2 &&
                SpecularChannels::kRgb == 0 && SpecularChannels::kCount == 4);
  GpuFrame& gpu = *ctx.gpu;
  GpuCommands& cmd = gpu.commands();
  const Buffer& hdr = ctx.input(*this, Slots::hdr);  // the shape (its value is on the device)
  PostfxDofArgs a{};
  a.hdr = ctx.deviceInput(*this, Slots::hdr);
  a.coc = ctx.deviceInput(*this, Slots::coc);
  a.specular = ctx.deviceInput(*this, Slots::specular);
  ctx.deviceOutput(*this, Slots::postfx);
  ctx.deviceOutput(*this, Slots::bokeh);
  const GpuBuffer& postfx = gpu.read(bufferName(Slots::postfx));
  const GpuBuffer& bokeh = gpu.read(bufferName(Slots::bokeh));
  const ThinLens lens = ThinLens::of(ctx.camera());
  if (!lens.active()) {  // a pinhole: nothing to blur
    cmd.copy(gpu.read(bufferName(Slots::hdr)), postfx, hdr.data.size() * sizeof(float));
    cmd.fill(bokeh, 0, hdr.pixelCount() * dof::BokehChannels::kCount * sizeof(float), 0);
    return;
  }
  a.width = uint32_t(hdr.width);
  a.height = uint32_t(hdr.height);
  a.halfWidth = (a.width + 1) / 2;
  a.halfHeight = (a.height + 1) / 2;
  a.tilesX = (a.halfWidth + TD_POSTFX_TILE - 1) / TD_POSTFX_TILE;
  a.tilesY = (a.halfHeight + TD_POSTFX_TILE - 1) / TD_POSTFX_TILE;
  const size_t halfPixels = size_t(a.halfWidth) * a.halfHeight;
  const size_t tiles = size_t(a.tilesX) * a.tilesY;
  const auto scratch = [&](const char* what, size_t floats) {
    return gpu.scratch("postfx_dof:" + name() + ":" + what, floats * sizeof(float)).address;
  };
  a.halfSamples = scratch("half", halfPixels * TD_HALF_SAMPLE);
  a.tileMax = scratch("tile_max", tiles);
  a.neighbourMax = scratch("neighbour_max", tiles);
  a.gathered = scratch("gathered", halfPixels * 3);
  a.bokeh = scratch("bokeh", halfPixels * 2);
  a.filtered = settings().median ? scratch("filtered", halfPixels * 3) : a.gathered;
  // The gather's taps and extents, then the prefilter's eight directions.
  const dof::GatherTaps pattern =
      dof::gatherTaps(lens, settings().polygon && lens.blades >= 3, ctx.serial);
  std::vector<float> taps;
  for (int i = 0; i < dof::kGatherTaps; ++i) {
    const dof::Tap& t = pattern.taps[size_t(i)];
    taps.insert(taps.end(),
                {t.x, t.y, t.dist, pattern.extentFar[size_t(i)], pattern.extentNear[size_t(i)]});
  }
  for (int t = 0; t < 8; ++t) {
    float c = 0, s = 0;
    dof::prefilterDirection(t, c, s);
    taps.insert(taps.end(), {c, s});
  }
  a.taps = gpu.constants(taps.data(), taps.size() * sizeof(float));
  a.lensK = lens.aperture * lens.pixelsPerSlope;
  a.focus = lens.focus;
  a.specularThreshold = settings().specularThreshold;
  a.bokehLuminance = settings().bokehLuminance;
  a.depthRange = settings().depthRange;
  a.invRange = a.depthRange > 0 ? 1.0f / a.depthRange : 0.0f;
  // The upscales: the colour (median-filtered) into postfx, the bokeh buffer into bokeh.
  PostfxDofArgs colour = a, intensity = a;
  colour.src = a.filtered;
  colour.dst = postfx.address;
  colour.channels = 3;
  intensity.src = a.bokeh;
  intensity.dst = bokeh.address;
  intensity.channels = 2;
  const uint64_t args = gpu.constants(&a, sizeof a);
  const GpuKernel& k =
      gpu.kernel("postfx_dof", kPostfxDofSpv, sizeof(kPostfxDofSpv) / 4, sizeof(DofStagePush));
  const auto stage = [&](uint32_t which, uint64_t record, uint32_t w, uint32_t h) {
    const DofStagePush push{record, which, 0};
    cmd.dispatch(k, (w + 7) / 8, (h + 7) / 8, 1, &push);
    cmd.barrier();
  };
  stage(TD_POSTFX_DOWNSAMPLE, args, a.halfWidth, a.halfHeight);
  stage(TD_POSTFX_TILE_MAX, args, a.tilesX, a.tilesY);
  stage(TD_POSTFX_NEIGHBOUR_MAX, args, a.tilesX, a.tilesY);
  stage(TD_POSTFX_PREFILTER, args, a.halfWidth, a.halfHeight);
  stage(TD_POSTFX_GATHER, args, a.halfWidth, a.halfHeight);
  if (settings().median) stage(TD_POSTFX_MEDIAN, args, a.halfWidth, a.halfHeight);
  stage(TD_POSTFX_UPSCALE, gpu.constants(&colour, sizeof colour), a.width, a.height);
  stage(TD_POSTFX_UPSCALE, gpu.constants(&intensity, sizeof intensity), a.width, a.height);
}

}  // namespace tandem
