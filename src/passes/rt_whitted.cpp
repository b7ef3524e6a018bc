#include "passes/rt_whitted.h"

#include "passes/rt_secondary.h"
#include "pipeline/frame_context.h"
#include "rt/primary_rays.h"
#include "rt/whitted.h"
#include "shading/surface_resolve.h"

namespace tandem {

std::vector<ParamDesc> RTWhittedPass::params() const {
  return whittedParams();
}

void RTWhittedPass::execute(FrameContext& ctx) {
  RayTracer& rt = ctx.rayTracer();
  const uint64_t before = rt.raysTraced();
  const Scene& scene = *ctx.scene;
  const ShadingContext shading = ShadingContext::from(scene);
  Whitted whitted(rt, scene, shading, whittedSettings(*this));
  Buffer& hdr = ctx.output(*this, "hdr");
  Buffer& ids = ctx.output(*this, "object_id");
  for (const View& v : ctx.views)
    tracePrimaryRays(v.camera, rt, [&](int x, int y, const Ray& r, const Hit& h) {
      x += v.x;
      y += v.y;
      if (!h.valid()) {
        hdr.setRgb(x, y, scene.skyRadiance(r.dir));
        ids.at(x, y)[0] = -1;
        return;
      }
      const float tuv[3] = {h.t, h.u, h.v};  // Embree's hit; the pixel's cone picks texture LOD
      SurfaceSample s = resolveSurface(ctx.frame, h.object, h.prim, r.origin, r.dir, r.time, tuv,
                                       ctx.pixelSpread(v));
      hdr.setRgb(x, y, whitted.shadePrimary(s, r.dir));
      ids.at(x, y)[0] = float(h.object);
    });
  // Primary rays are counted by the tracer too, so the delta covers every ray of the pass.
  ctx.passRays += double(rt.raysTraced() - before);
}

}  // namespace tandem
