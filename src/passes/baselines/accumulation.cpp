#include "passes/baselines/accumulation.h"

#include <algorithm>
#include <memory>
#include <numeric>
#include <random>

#include "core/low_discrepancy.h"
#include "core/parallel.h"
#include "passes/common/time_lens_camera.h"
#include "pipeline/frame_context.h"
#include "rt/reference_render.h"
#include "rt/whitted.h"
#include "shading/blinn_phong.h"
#include "shading/surface_resolve.h"

namespace tandem {

const ParamTable<AccumulationSettings>& AccumulationPass::tableFor() const {
  using S = AccumulationSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::samples, {.name = "samples",
                             .min = 1,
                             .max = 4096,
                             .doc = "rasterized images averaged",
                             .invalidatesHistory = true})
          .add(&S::mode, {.name = "mode",
                          .doc = "what the samples vary",
                          .choices = {"dof", "motion_blur", "both"},
                          .invalidatesHistory = true})
          .add(&S::antialias, {.name = "antialias", .doc = "jitter each image within the pixel"})
          .add(&S::shading,
               {.name = "shading",
                .doc = "whitted: ray-traced shadows, mirrors, glass (as interleaved_*); local: "
                       "Blinn-Phong without shadows",
                .choices = {"whitted", "local"},
                .invalidatesHistory = true});
  return table;
}

std::vector<CounterDesc> AccumulationPass::counters() const {
  return {
      {AccumulationCounters::trianglesBinned, "triangles binned over all sub-frames"},
  };
}

void AccumulationPass::execute(FrameContext& ctx) {
  const AccumulationSettings& s = settings();
  const int n = s.samples;
  const bool lens = s.mode != AccumulationSettings::Mode::MotionBlur,
             time = s.mode != AccumulationSettings::Mode::Dof, aa = s.antialias;
  const Scene& scene = *ctx.scene;
  const ShadingContext shading = ShadingContext::from(scene);
  RayTracer* rt = s.shading == AccumulationSettings::Shading::Whitted ? &ctx.rayTracer() : nullptr;
  const uint64_t raysBefore = rt ? rt->raysTraced() : 0;
  const std::vector<TimeLensPair> pairs = stratifiedTimeLensPairs(n, ctx.seed);
  Buffer& hdr = ctx.output(*this, Slots::hdr);
  hdr.fill(0.0f);
  const float weight = 1.0f / float(n);
  double rasterMs = 0, shadeMs = 0;
  uint64_t triangles = 0;
  for (const View& v : ctx.views) {
    for (const TimeLensPair& p : pairs) {
      const float tau = time ? p.tau : 0.0f;
      // The camera along its shutter path, then moved to the lens point.
      const Camera cam = cameraForPair(v, p, time, lens, aa ? v.jitter + p.jitter : v.jitter);
      auto t0 = Clock::now();
      RasterStats stats;
      rasterizer_.render(ctx.frame, cam, visibility_, &stats, time ? tau : -1.0f);
      triangles += stats.trianglesBinned;
      rasterMs += msSince(t0);
      auto t1 = Clock::now();
      std::unique_ptr<Whitted> whitted;
      if (rt) whitted = std::make_unique<Whitted>(Whitted(*rt, scene, shading, {}).atTime(tau));
      parallelTiles(v.width(), v.height(), [&](int x0, int y0, int x1, int y1) {
        for (int y = y0; y < y1; ++y)
          for (int x = x0; x < x1; ++x) {
            const size_t i = size_t(y) * size_t(v.width()) + size_t(x);
            Vec3 o, d;
            cam.generateRay(float(x) + 0.5f, float(y) + 0.5f, o, d);
            Vec3 c;
            if (visibility_.object[i] == kNoObject) {
              c = scene.skyRadiance(d);
            } else {
              const SurfaceSample s = resolveSurface(ctx.frame, int(visibility_.object[i]),
                                                     int(visibility_.prim[i]), o, d, tau);
              c = whitted ? whitted->shadePrimary(s, d) : shadeBlinnPhong(s, -d, shading);
            }
            float* h = hdr.at(x + v.x, y + v.y);
            h[0] += c.x * weight;
            h[1] += c.y * weight;
            h[2] += c.z * weight;
          }
      });
      shadeMs += msSince(t1);
    }
  }
  ctx.passParts.push_back({"raster", rasterMs, 0});
  ctx.passParts.push_back({"shade", shadeMs, 0});
  ctx.report(*this, AccumulationCounters::trianglesBinned, double(triangles));
  if (rt) ctx.passRays += double(rt->raysTraced() - raysBefore);
}

}  // namespace tandem
