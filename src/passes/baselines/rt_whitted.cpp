#include "passes/baselines/rt_whitted.h"

#include "gpu/gpu_camera.h"
#include "gpu/shaders/rt_whitted_spv.h"
#include "gpu/shaders/whitted_args.h"
#include "passes/common/gpu_shadow_maps.h"
#include "passes/common/gpu_whitted.h"
#include "passes/common/whitted_settings.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"
#include "rt/primary_rays.h"
#include "rt/whitted.h"
#include "shading/surface_resolve.h"

namespace tandem {

const ParamTable<RTWhittedSettings>& RTWhittedPass::tableFor() const {
  static const ParamTable<RTWhittedSettings> table =
      ParamTable<RTWhittedSettings>().nest(&RTWhittedSettings::whitted, whittedTable());
  return table;
}

void RTWhittedPass::execute(FrameContext& ctx) {
  WhittedFrame wf(ctx, *this, settings().whitted);
  const Scene& scene = *ctx.scene;
  Buffer& hdr = ctx.output(*this, Slots::hdr);
  Buffer& ids = ctx.output(*this, Slots::objectId);
  for (const View& v : ctx.views) {
    const float spread = ctx.pixelSpread(v);  // the pixel's cone picks texture LOD
    tracePrimaryBlocks(
        v.jitteredCamera, wf.rt,
        [&](int n, const int* px, const int* py, const Ray* rs, const Hit* hits) {
          // The block's surfaces are shaded together: shadow rays as packets, one batch.
          SurfaceSample s[8];
          Vec3 d[8], rgb[8];
          int at[8], m = 0;
          for (int k = 0; k < n; ++k) {
            const int x = px[k] + v.x, y = py[k] + v.y;
            const Hit& h = hits[k];
            ids.at(x, y)[0] = h.valid() ? float(h.object) : -1.0f;
            if (!h.valid()) {
              hdr.setRgb(x, y, scene.skyRadiance(rs[k].dir));
              continue;
            }
            const float tuv[3] = {h.t, h.u, h.v};  // Embree's hit: no second intersection
            s[m] = resolveSurface(ctx.frame, h.object, h.prim, rs[k].origin, rs[k].dir, rs[k].time,
                                  tuv, spread);
            d[m] = rs[k].dir;
            at[m++] = k;
          }
          wf.whitted.shadePrimary8(s, d, m, rgb);
          for (int j = 0; j < m; ++j) hdr.setRgb(px[at[j]] + v.x, py[at[j]] + v.y, rgb[j]);
        });
  }
  wf.finish(ctx, *this, double(ctx.width) * double(ctx.height));
}

void RTWhittedPass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  const GpuScene& scene = gpu.scene(ctx.frame);
  const WhittedSettings w = settings().whitted.settings();
  WhittedArgs a{};
  a.scene = scene.sceneAddress();
  a.hdr = ctx.deviceOutput(*this, Slots::hdr);
  a.objectId = ctx.deviceOutput(*this, Slots::objectId);
  const uint32_t zero[TD_COUNT_N] = {};
  a.counters = gpu.constants(zero, sizeof zero);
  a.frameWidth = ctx.width;
  a.maxDepth = w.maxDepth;
  a.importanceCutoff = w.importanceCutoff;
  a.shadowCull = w.shadowCull;
  // Classified and shadow-map shadows: the frame's maps (every light that casts shadows), drawn
  // on the device where they changed.
  const ShadowMaps* maps = shadowMapsFor(ctx, *this, settings().whitted, nullptr, true);
  a.shadowMaps = maps ? gpuShadowMaps(ctx, *maps) : 0;
  a.flags = gpuWhittedFlags(w, maps != nullptr);
  const GpuKernel& k =
      gpu.kernel("rt_whitted", kRtWhittedSpv, sizeof(kRtWhittedSpv) / 4, sizeof(WhittedArgs));
  for (const View& v : ctx.views) {
    const GpuCamera cam = gpuCamera(v.jitteredCamera, ctx.pixelSpread(v));
    a.camera = gpu.constants(&cam, sizeof cam);
    a.viewX = v.x;
    a.viewY = v.y;
    gpu.dispatchInterruptibly(k, uint32_t(v.width() + 7) / 8, uint32_t(v.height() + 7) / 8, &a);
  }
  // The counters are read once the frame's commands completed.
  const auto* counts = static_cast<const uint32_t*>(gpu.constantsData(a.counters));
  const double pixels = double(ctx.width) * double(ctx.height);
  gpu.afterSubmit([this, &ctx, counts, pixels] { reportGpuShadows(ctx, *this, counts, pixels); });
}

}  // namespace tandem
