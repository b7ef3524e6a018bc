// rt_dof on the GPU: the lens rays of every mask pixel in one dispatch (shaders/rt_dof.comp),
// with the seed, lens and cameras the CPU pass takes, so both trace the same rays.
#include <cstring>
#include <vector>

#include "gpu/gpu_camera.h"
#include "gpu/shaders/rt_dof_args.h"
#include "gpu/shaders/rt_dof_spv.h"
#include "gpu/shaders/whitted_args.h"
#include "passes/common/gpu_shadow_maps.h"
#include "passes/common/gpu_whitted.h"
#include "passes/dof/rt_dof.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"
#include "scene/thin_lens.h"

namespace tandem {

void RTDofPass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  const Buffer& mask = ctx.input(*this, Slots::rayMask);  // the shape (its value is on the device)
  const int w = mask.width, h = mask.height;
  RtDofArgs a{};
  a.scene = gpu.scene(ctx.frame).sceneAddress();
  a.mask = ctx.deviceInput(*this, Slots::rayMask);
  a.rtNear = ctx.deviceOutput(*this, Slots::rtNear, w, h);
  a.rtFar = ctx.deviceOutput(*this, Slots::rtFar, w, h);
  a.rtHit = ctx.deviceOutput(*this, Slots::rtHit, w, h);
  a.rtFarPosition = ctx.deviceOutput(*this, Slots::rtFarPosition, w, h);
  if (settings().reuseRaster && ctx.optionalInput(*this, Slots::hdr) &&
      ctx.optionalInput(*this, Slots::depth)) {
    a.sharp = ctx.deviceInput(*this, Slots::hdr);
    a.depth = ctx.deviceInput(*this, Slots::depth);
  }
  // The unjittered cameras (RTDofPass::execute: the rays jitter over the pixel themselves).
  const float scale = float(ctx.width) / float(w);
  const float spread = ctx.pixelSpread(ctx.views.front()) * scale;
  std::vector<RtDofView> views;
  for (const View& v : ctx.views) {
    RtDofView g{};
    g.camera = gpuCamera(v.camera, spread);
    std::memcpy(g.viewProj, &v.camera.viewProj.m[0][0], sizeof g.viewProj);
    g.x = v.x;
    g.y = v.y;
    g.width = v.width();
    g.height = v.height();
    views.push_back(g);
  }
  a.views = gpu.constants(views.data(), views.size() * sizeof(RtDofView));
  const std::vector<uint32_t> zero(TD_COUNT_N + TD_RT_DOF_COUNTS, 0);
  a.counters = gpu.constants(zero.data(), zero.size() * sizeof(uint32_t));
  const WhittedSettings ws = settings().whitted.settings();
  const ShadowMaps* maps = shadowMapsFor(ctx, *this, settings().whitted, nullptr, true);
  a.shadowMaps = maps ? gpuShadowMaps(ctx, *maps) : 0;
  a.flags = gpuWhittedFlags(ws, maps != nullptr);
  a.maxDepth = ws.maxDepth;
  a.importanceCutoff = ws.importanceCutoff;
  a.shadowCull = ws.shadowCull;
  a.maskWidth = uint32_t(w);
  a.maskHeight = uint32_t(h);
  a.frameWidth = uint32_t(ctx.width);
  a.frameHeight = uint32_t(ctx.height);
  a.viewCount = uint32_t(views.size());
  // New lens samples every executed frame, as on the CPU.
  const uint64_t seed = ctx.frameSeed();
  a.seedLo = uint32_t(seed);
  a.seedHi = uint32_t(seed >> 32);
  const Camera& cam = ctx.views.front().camera;
  const ThinLens lens = ThinLens::of(cam);  // the same lens in every view
  a.scale = scale;
  a.spread = spread;
  a.nearT = cam.desc.nearPlane;
  a.lensK = lens.aperture * lens.pixelsPerSlope;
  a.focus = lens.focus;
  a.apertureRadius = 0.5f * cam.desc.apertureDiameter;
  a.apertureRotation = radians(cam.desc.apertureRotationDeg);
  a.apertureBlades = cam.desc.apertureBlades;
  const uint64_t args = gpu.constants(&a, sizeof a);
  const GpuKernel& k = gpu.kernel("rt_dof", kRtDofSpv, sizeof(kRtDofSpv) / 4, sizeof args);
  gpu.dispatchInterruptibly(k, uint32_t(w + 7) / 8, uint32_t(h + 7) / 8, &args);
  // The counters are read once the batch has run.
  const auto* counts = static_cast<const uint32_t*>(gpu.constantsData(a.counters));
  const double pixels = double(w) * double(h);
  gpu.afterSubmit([this, &ctx, counts, pixels] {
    reportGpuShadows(ctx, *this, counts, pixels);
    const double lensRays = counts[TD_COUNT_N + TD_RT_DOF_LENS_RAYS];
    ctx.report(*this, RTDofCounters::lensRays, lensRays);
    ctx.report(*this, RTDofCounters::reusedShare,
               lensRays > 0 ? counts[TD_COUNT_N + TD_RT_DOF_REUSED] / lensRays : 0.0);
  });
}

}  // namespace tandem
