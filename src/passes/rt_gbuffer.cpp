#include "passes/rt_gbuffer.h"

#include <atomic>

#include "core/parallel.h"
#include "pipeline/frame_context.h"
#include "raster/gbuffer.h"
#include "shading/surface_resolve.h"

namespace tandem {

std::vector<BufferSlot> RTGBufferPass::outputs() const {
  return gbufferSlots();
}

void RTGBufferPass::execute(FrameContext& ctx) {
  RayTracer& rt = ctx.rayTracer();
  GBufferView g = GBufferView::create(ctx, *this);
  std::atomic<uint64_t> rays{0};
  parallelTiles(ctx.width, ctx.height, [&](int x0, int y0, int x1, int y1) {
    uint64_t local = 0;
    for (int by = y0; by < y1; by += 2)
      for (int bx = x0; bx < x1; bx += 4) {
        Ray rs[8];
        int px[8], py[8], n = 0;
        for (int j = 0; j < 2; ++j)
          for (int i = 0; i < 4; ++i) {
            int x = bx + i, y = by + j;
            if (x >= x1 || y >= y1) continue;
            ctx.camera.generateRay(x + 0.5f, y + 0.5f, rs[n].origin, rs[n].dir);
            // Start at the near plane, exactly where the rasterizer clips.
            float cosAxis = dot(rs[n].dir, ctx.camera.forward);
            rs[n].tnear = ctx.camera.desc.projection == Projection::Perspective
                              ? ctx.camera.desc.nearPlane / std::max(cosAxis, 1e-6f)
                              : ctx.camera.desc.nearPlane;
            px[n] = x;
            py[n] = y;
            ++n;
          }
        Hit hits[8];
        rt.intersect8(rs, n, hits, /*cullBackfaces=*/true);
        local += uint64_t(n);
        for (int k = 0; k < n; ++k) {
          const Hit& h = hits[k];
          if (!h.valid()) {
            g.writeBackground(px[k], py[k], backgroundMotion(ctx, rs[k].dir));
            continue;
          }
          SurfaceSample s = resolveSurface(ctx.frame, h.object, h.prim, rs[k].origin, rs[k].dir);
          float depth = ctx.camera.depthOf(rs[k].origin + rs[k].dir * h.t);
          g.write(px[k], py[k], s, depth, motionVector(ctx, s.object, s.position));
        }
      }
    rays += local;
  });
  ctx.passRays += double(rays.load());
}

}  // namespace tandem
