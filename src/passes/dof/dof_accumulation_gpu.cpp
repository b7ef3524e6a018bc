// dof_accumulation on the GPU: the per-pixel accumulation in one dispatch
// (shaders/dof_accumulation.comp), then the variance's Gaussian blur (convolve.comp); its
// counters summed by 64-bit integer atomics and read once the batch has run.
#include <algorithm>
#include <cstring>
#include <vector>

#include "core/image_filters.h"
#include "gpu/shaders/dof_accumulation_spv.h"
#include "gpu/shaders/dof_args.h"
#include "passes/common/gpu_filters.h"
#include "passes/dof/dof_accumulation.h"
#include "passes/dof/dof_common.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"

namespace tandem {

void DofAccumulationPass::executeGpu(FrameContext& ctx) {
  static_assert(dof::AccChannels::kCount == 5 && dof::AccChannels::kShare == 3 &&
                dof::AccChannels::kCoc == 4 && dof::MomentChannels::kCount == 3 &&
                dof::RtChannels::kCount == 9 && dof::kLayerChannels == 4 &&
                dof::kHitChannels == 2 && dof::kFarPositionChannels == 4);
  GpuFrame& gpu = *ctx.gpu;
  const Buffer& nearIn = ctx.input(*this, Slots::rtNear);  // shapes (values on the device)
  const Buffer& motion = ctx.input(*this, Slots::motion);
  const int w = nearIn.width, h = nearIn.height;
  DofAccumulationArgs a{};
  a.rtNear = ctx.deviceInput(*this, Slots::rtNear);
  a.rtFar = ctx.deviceInput(*this, Slots::rtFar);
  a.rtHit = ctx.deviceInput(*this, Slots::rtHit);
  a.rtFarPosition = ctx.deviceInput(*this, Slots::rtFarPosition);
  a.motion = ctx.deviceInput(*this, Slots::motion);
  // Last frame's accumulation, all three or none (as on the CPU: a size change starts over).
  const auto fits = [&](const char* slot) {
    const Buffer* b = ctx.previous(*this, slot);
    return b && b->width == w && b->height == h;
  };
  if (fits(Slots::accNear) && fits(Slots::accFar) && fits(Slots::accMoments)) {
    a.prevNear = ctx.devicePrevious(*this, Slots::accNear);
    a.prevFar = ctx.devicePrevious(*this, Slots::accFar);
    a.prevMoments = ctx.devicePrevious(*this, Slots::accMoments);
  }
  a.accNear = ctx.deviceOutput(*this, Slots::accNear, w, h);
  a.accFar = ctx.deviceOutput(*this, Slots::accFar, w, h);
  a.accMoments = ctx.deviceOutput(*this, Slots::accMoments, w, h);
  a.rtColor = ctx.deviceOutput(*this, Slots::rtColor, w, h);
  const uint64_t varianceOut = ctx.deviceOutput(*this, Slots::dofVariance, w, h);
  const size_t bytes = size_t(w) * size_t(h) * sizeof(float);
  a.variance = gpu.scratch("dof_accumulation:" + name() + ":variance", bytes).address;
  std::vector<DofAccumulationView> views;
  for (const View& v : ctx.views) {
    DofAccumulationView g{};
    std::memcpy(g.prevViewProj, &v.prevCamera.viewProj.m[0][0], sizeof g.prevViewProj);
    g.x = v.x;
    g.y = v.y;
    g.width = v.prevCamera.width;
    g.height = v.prevCamera.height;
    g.cameraMoved = v.cameraMoved ? 1 : 0;
    g.perspective = v.prevCamera.desc.projection == Projection::Perspective ? 1 : 0;
    views.push_back(g);
  }
  a.views = gpu.constants(views.data(), views.size() * sizeof(DofAccumulationView));
  const uint64_t zero[2] = {0, 0};
  a.counters = gpu.constants(zero, sizeof zero);
  a.width = uint32_t(w);
  a.height = uint32_t(h);
  a.frameWidth = uint32_t(ctx.width);
  a.frameHeight = uint32_t(ctx.height);
  a.motionWidth = uint32_t(motion.width);
  a.motionHeight = uint32_t(motion.height);
  a.viewCount = uint32_t(views.size());
  a.adaptive = settings().adaptiveAlpha ? 1 : 0;
  a.scale = float(ctx.width) / float(w);
  a.minAlpha = 1.0f - settings().historyWeight;
  a.motionPixels = settings().motionPixels;
  const uint64_t args = gpu.constants(&a, sizeof a);
  const GpuKernel& k = gpu.kernel("dof_accumulation", kDofAccumulationSpv,
                                  sizeof(kDofAccumulationSpv) / 4, sizeof args);
  GpuCommands& cmd = gpu.commands();
  cmd.dispatch(k, uint32_t(w + 7) / 8, uint32_t(h + 7) / 8, 1, &args);
  cmd.barrier();
  // The variance blurred for the next frame's ray mask and the reconstruction.
  const std::vector<float> kernel = gaussianKernel(settings().varianceBlur);
  if (kernel.empty())  // variance_blur 0
    cmd.copy(gpu.scratch("dof_accumulation:" + name() + ":variance", bytes),
             gpu.read(bufferName(Slots::dofVariance)), bytes);
  else
    recordSeparableFilter(gpu, a.variance, varianceOut,
                          gpu.scratch("dof_accumulation:" + name() + ":blur", bytes).address, w, h,
                          1, kernel, kernel);
  const auto* counts = static_cast<const uint64_t*>(gpu.constantsData(a.counters));
  const double n = double(std::max(1, w * h));
  gpu.afterSubmit([this, &ctx, counts, n] {
    ctx.report(*this, DofAccumulationCounters::meanVariance, double(counts[0]) / 4294967296.0 / n);
    ctx.report(*this, DofAccumulationCounters::varianceAbove1e6, double(counts[1]) / n);
  });
}

}  // namespace tandem
