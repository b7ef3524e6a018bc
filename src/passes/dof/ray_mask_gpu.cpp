// ray_mask on the GPU: RayMaskPass's steps as the stages of shaders/ray_mask.comp, the Gaussian
// and the 5x5 Sobel through convolve.comp with the CPU's kernels; the counters by 64-bit integer
// atomics, read once the batch has run.
#include <cstring>
#include <string>
#include <vector>

#include "core/image_filters.h"
#include "gpu/shaders/dof_args.h"
#include "gpu/shaders/ray_mask_spv.h"
#include "passes/common/gpu_filters.h"
#include "passes/dof/ray_mask.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"

namespace tandem {

void RayMaskPass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  GpuCommands& cmd = gpu.commands();
  const RayMaskSettings& cfg = settings();
  const int scale = cfg.resolution == RayMaskSettings::Resolution::Half ? 2 : 1;
  const int W = ctx.width, H = ctx.height, w = (W + scale - 1) / scale, h = (H + scale - 1) / scale;
  RayMaskArgs a{};
  a.mask = ctx.deviceOutput(*this, Slots::rayMask, w, h);
  if (cfg.mode == RayMaskSettings::Mode::All) {  // m rays everywhere (no counters, as on the CPU)
    const float m = float(cfg.m);
    uint32_t bits = 0;
    std::memcpy(&bits, &m, sizeof bits);
    cmd.fill(gpu.read(bufferName(Slots::rayMask)), 0, size_t(w) * h * sizeof(float), bits);
    return;
  }
  a.position = ctx.deviceInput(*this, Slots::position);
  a.normal = ctx.deviceInput(*this, Slots::normal);
  a.depth = ctx.deviceInput(*this, Slots::depth);
  a.coc = ctx.deviceInput(*this, Slots::coc);
  const bool bokeh = ctx.optionalInput(*this, Slots::bokeh) != nullptr;
  a.bokeh = bokeh ? ctx.deviceInput(*this, Slots::bokeh) : 0;
  const Buffer* variance = ctx.previous(*this, Slots::dofVariance);
  if (variance && variance->width == w && variance->height == h)
    a.variance = ctx.devicePrevious(*this, Slots::dofVariance);
  const auto scratch = [&](const char* what, size_t floats) {
    return gpu.scratch("ray_mask:" + name() + ":" + what, floats * sizeof(float)).address;
  };
  const size_t frame = size_t(W) * H, mask = size_t(w) * h;
  a.inverseDepth = scratch("input", 4 * frame);
  a.blurred = scratch("blurred", 4 * frame);
  a.low = scale == 2 ? scratch("low", 4 * mask) : a.blurred;
  a.gx = scratch("gx", 4 * mask);
  a.gy = scratch("gy", 4 * mask);
  a.nearFine = scratch("near_fine", 2 * mask);
  const uint64_t temp = scratch("temp", 4 * frame);  // the separable filters' between passes
  a.width = uint32_t(W);
  a.height = uint32_t(H);
  a.maskWidth = uint32_t(w);
  a.maskHeight = uint32_t(h);
  a.scale = uint32_t(scale);
  a.tilesX = (a.maskWidth + TD_MASK_TILE - 1) / TD_MASK_TILE;
  a.tilesY = (a.maskHeight + TD_MASK_TILE - 1) / TD_MASK_TILE;
  a.tileMax = scratch("tile_max", size_t(a.tilesX) * a.tilesY);
  a.tileNear = scratch("tile_near", size_t(a.tilesX) * a.tilesY);
  a.dilate = cfg.dilate ? 1 : 0;
  const Camera& cam = ctx.camera();
  a.eyeX = cam.eye.x, a.eyeY = cam.eye.y, a.eyeZ = cam.eye.z;
  a.forwardX = cam.forward.x, a.forwardY = cam.forward.y, a.forwardZ = cam.forward.z;
  a.focus = cam.desc.focusDistance;
  a.fineCoc = bokeh ? 0.5f * cfg.fineCoc : 0.0f;
  a.s = cfg.s;
  a.varianceWeight = cfg.varianceWeight;
  a.m = float(cfg.m);
  const uint64_t zero[2] = {0, 0};
  a.counters = gpu.constants(zero, sizeof zero);
  const uint64_t args = gpu.constants(&a, sizeof a);
  const GpuKernel& k =
      gpu.kernel("ray_mask", kRayMaskSpv, sizeof(kRayMaskSpv) / 4, sizeof(DofStagePush));
  const auto stage = [&](uint32_t which, uint32_t gw, uint32_t gh) {
    const DofStagePush push{args, which, 0};
    cmd.dispatch(k, (gw + 7) / 8, (gh + 7) / 8, 1, &push);
    cmd.barrier();
  };
  // gradients(): d / z and normals, Gaussian-filtered (σ = 1 px), reduced, differentiated.
  stage(TD_MASK_INPUT, a.width, a.height);
  const std::vector<float> gauss = gaussianKernel(1.0f);
  recordSeparableFilter(gpu, a.inverseDepth, a.blurred, temp, W, H, 4, gauss, gauss);
  if (scale == 2) stage(TD_MASK_DOWNSAMPLE, a.maskWidth, a.maskHeight);
  const std::vector<float> smooth = {1, 4, 6, 4, 1}, derive = {-1, -2, 0, 2, 1};  // sobel5x5
  recordSeparableFilter(gpu, a.low, a.gx, temp, w, h, 4, derive, smooth);
  recordSeparableFilter(gpu, a.low, a.gy, temp, w, h, 4, smooth, derive);
  stage(TD_MASK_NEAR, a.maskWidth, a.maskHeight);
  if (cfg.dilate) {
    stage(TD_MASK_TILE_MAX, a.tilesX, a.tilesY);
    stage(TD_MASK_NEIGHBOUR_MAX, a.tilesX, a.tilesY);
  }
  stage(TD_MASK_RAYS, a.maskWidth, a.maskHeight);
  const auto* counts = static_cast<const uint64_t*>(gpu.constantsData(a.counters));
  const double pixels = double(mask);
  gpu.afterSubmit([this, &ctx, counts, pixels] {
    ctx.report(*this, RayMaskCounters::raysPerPixel, double(counts[0]) / pixels);
    ctx.report(*this, RayMaskCounters::maskedShare, double(counts[1]) / pixels);
  });
}

}  // namespace tandem
