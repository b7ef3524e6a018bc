#include "passes/rt_gbuffer.h"

#include <tbb/enumerable_thread_specific.h>
#include "pipeline/gbuffer_io.h"
#include "rt/primary_rays.h"

#include "shading/surface_resolve.h"
#include "shading/surface_resolve_inline.h"

namespace tandem {

std::vector<BufferSlot> RTGBufferPass::outputs() const {
  return gbufferSlots();
}

void RTGBufferPass::execute(FrameContext& ctx) {
  RayTracer& rt = ctx.rayTracer();
  GBufferView g = gbufferTargets(ctx, *this);
  // Each worker's recently set-up triangles (neighbouring rays mostly hit the same ones).
  tbb::enumerable_thread_specific<TriangleSetupCache<>> caches;
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
          const SurfaceSample s = [&] {
            if (!ctx.frame.objects[size_t(h.object)].stepPositions.empty())
              return resolveSurface(ctx.frame, h.object, h.prim, r.origin, r.dir, r.time, tuv,
                                    spread);
            bool fresh;
            const TriangleSetup& tri =
                caches.local().get(ctx.frame, uint32_t(h.object), uint32_t(h.prim), fresh).setup;
            return resolveSurfaceInline(tri, r.origin, r.dir, tuv, spread);
          }();
          float depth = v.camera.depthOf(r.origin + r.dir * h.t);
          g.write(x + v.x, y + v.y, s, depth, motionVector(ctx.frame, v, s.object, s.position));
        }));
  }
}

}  // namespace tandem
