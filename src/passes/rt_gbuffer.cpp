#include "passes/rt_gbuffer.h"

#include "pipeline/frame_context.h"
#include "raster/gbuffer.h"
#include "rt/primary_rays.h"
#include "shading/surface_resolve.h"

namespace tandem {

std::vector<BufferSlot> RTGBufferPass::outputs() const {
  return gbufferSlots();
}

void RTGBufferPass::execute(FrameContext& ctx) {
  RayTracer& rt = ctx.rayTracer();
  GBufferView g = GBufferView::create(ctx, *this);
  ctx.passRays +=
      double(tracePrimaryRays(ctx.camera, rt, [&](int x, int y, const Ray& r, const Hit& h) {
        if (!h.valid()) {
          g.writeBackground(x, y, backgroundMotion(ctx, r.dir));
          return;
        }
        SurfaceSample s = resolveSurface(ctx.frame, h.object, h.prim, r.origin, r.dir);
        float depth = ctx.camera.depthOf(r.origin + r.dir * h.t);
        g.write(x, y, s, depth, motionVector(ctx, s.object, s.position));
      }));
}

}  // namespace tandem
