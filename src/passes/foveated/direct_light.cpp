#include "passes/foveated/direct_light.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>

#include "passes/foveated/primary_surface.h"
#include "pipeline/frame_context.h"
#include "rt/diffuse_gi.h"
#include "scene/scene.h"

namespace tandem {

std::vector<BufferSlot> DirectLightPass::inputs() const {
  return PrimarySurfaces::slots();
}

const ParamTable<DirectLightSettings>& DirectLightPass::tableFor() const {
  using S = DirectLightSettings;
  static const ParamTable<S> table = ParamTable<S>().add(
      &S::lights, {.name = "lights",
                   .min = 0,
                   .max = 64,
                   .doc = "lights traced per pixel, those giving it the most unshadowed light; "
                          "the others stay in the path-traced estimate"});
  return table;
}

void DirectLightPass::execute(FrameContext& ctx) {
  const PrimarySurfaces g = PrimarySurfaces::of(ctx, *this);
  Buffer& out = ctx.output(*this, Slots::ptDirect);
  const RayTracer& rt = ctx.rayTracer();
  const ShadingContext shading = ShadingContext::from(*ctx.scene);
  const DiffuseGI gi(rt, *ctx.scene, shading);
  const int count = settings().lights;
  std::atomic<uint64_t> rays{0};
  for (const View& v : ctx.views)
    tbb::parallel_for(tbb::blocked_range<int>(0, v.height()), [&](const auto& rows) {
      uint64_t local = 0;
      // Surfaces gathered 8 at a time along the row: their shadow rays go as packets.
      SurfaceSample s[8];
      Vec3 wo[8], lit[8];
      int xs[8], ys[8], n = 0;
      auto flush = [&] {
        gi.brightestDirect8(s, wo, n, count, 0.0f, lit, local);
        for (int j = 0; j < n; ++j)
          out.setRgb(xs[j], ys[j],
                     DiffuseGI::emitted(s[j], wo[j]) + DiffuseGI::albedo(s[j]) * lit[j]);
        n = 0;
      };
      for (int ey = rows.begin(); ey != rows.end(); ++ey) {
        for (int ex = 0; ex < v.width(); ++ex) {
          const int x = ex + v.x, y = ey + v.y;
          if (g.sky(x, y)) {  // the sky, as foveated_pt sees it
            Vec3 o, d;
            v.jitteredCamera.generateRay(ex + 0.5f, ey + 0.5f, o, d);
            out.setRgb(x, y, ctx.scene->skyRadiance(d));
            continue;
          }
          s[n] = g.at(x, y);
          wo[n] = PrimarySurfaces::towardsViewer(v, s[n].position);
          xs[n] = x, ys[n] = y;
          if (++n == 8) flush();
        }
        if (n > 0) flush();
      }
      rays += local;
    });
  ctx.passRays += double(rays.load());
}

}  // namespace tandem
