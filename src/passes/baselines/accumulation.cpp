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

std::vector<ParamDesc> AccumulationPass::params() const {
  return {{"samples", ParamType::Int, 64, 1, 4096, "rasterized images averaged", {}, true},
          {"mode",
           ParamType::Enum,
           2,
           0,
           2,
           "what the samples vary",
           {"dof", "motion_blur", "both"},
           true},
          {"antialias", ParamType::Bool, 1, 0, 1, "jitter each image within the pixel", {}},
          {"shading",
           ParamType::Enum,
           1,
           0,
           1,
           "whitted: ray-traced shadows, mirrors, glass (as interleaved_*); local: Blinn-Phong "
           "without shadows",
           {"whitted", "local"},
           true}};
}

void AccumulationPass::execute(FrameContext& ctx) {
  const int n = int(param("samples")), mode = int(param("mode"));
  const bool lens = mode != 1, time = mode != 0, aa = param("antialias") != 0;
  const Scene& scene = *ctx.scene;
  const ShadingContext shading = ShadingContext::from(scene);
  RayTracer* rt = param("shading") == 0 ? &ctx.rayTracer() : nullptr;
  const uint64_t raysBefore = rt ? rt->raysTraced() : 0;
  const std::vector<TimeLensPair> pairs = stratifiedTimeLensPairs(n, ctx.seed);
  Buffer& hdr = ctx.output(*this, "hdr");
  hdr.fill(0.0f);
  const float weight = 1.0f / float(n);
  double rasterMs = 0, shadeMs = 0;
  uint64_t triangles = 0;
  for (const View& v : ctx.views) {
    for (const TimeLensPair& p : pairs) {
      const float tau = time ? p.tau : 0.0f;
      // The camera along its shutter path, then moved to the lens point.
      const Camera cam =
          cameraForPair(v, p, time, lens, aa ? v.camera.jitter + p.jitter : v.camera.jitter);
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
  ctx.counters["accumulation/triangles_binned"] = double(triangles);
  if (rt) ctx.passRays += double(rt->raysTraced() - raysBefore);
}

}  // namespace tandem
