#include "passes/rt_gbuffer.h"

#include "pipeline/gbuffer_io.h"
#include "rt/primary_rays.h"
#include "shading/surface_resolve.h"

namespace tandem {

std::vector<BufferSlot> RTGBufferPass::outputs() const {
  return gbufferSlots();
}

void RTGBufferPass::execute(FrameContext& ctx) {
  RayTracer& rt = ctx.rayTracer();
  GBufferView g = gbufferTargets(ctx, *this);
  for (const View& v : ctx.views) {
    const float spread = ctx.pixelSpread(v);  // texture level of detail, as raster
    ctx.passRays +=
        double(tracePrimaryRays(v.camera, rt, [&](int x, int y, const Ray& r, const Hit& h) {
          if (!h.valid()) {
            g.writeBackground(x + v.x, y + v.y, backgroundMotion(v, r.dir));
            return;
          }
          // Embree's own distance and barycentrics: no second intersection.
          const float tuv[3] = {h.t, h.u, h.v};
          SurfaceSample s =
              resolveSurface(ctx.frame, h.object, h.prim, r.origin, r.dir, r.time, tuv, spread);
          float depth = v.camera.depthOf(r.origin + r.dir * h.t);
          g.write(x + v.x, y + v.y, s, depth, motionVector(ctx.frame, v, s.object, s.position));
        }));
  }
}

}  // namespace tandem
