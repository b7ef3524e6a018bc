#include "passes/raster_gbuffer.h"

#include "core/parallel.h"
#include "pipeline/frame_context.h"
#include "raster/gbuffer.h"
#include "shading/surface_resolve.h"

namespace tandem {

std::vector<BufferSlot> RasterGBufferPass::outputs() const {
  return gbufferSlots();
}

void RasterGBufferPass::execute(FrameContext& ctx) {
  auto t0 = Clock::now();
  ctx.rasterizer.render(ctx.frame, ctx.camera, ctx.visibility, &ctx.rasterStats);
  ctx.passParts.push_back({"visibility", msSince(t0), 0});
  auto t1 = Clock::now();
  GBufferView g = GBufferView::create(ctx, *this);
  const VisibilityBuffer& vis = ctx.visibility;
  parallelTiles(ctx.width, ctx.height, [&](int x0, int y0, int x1, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        size_t i = size_t(y) * ctx.width + x;
        // Barycentrics come from the pixel's camera ray against the visible triangle, which is
        // exact and perspective-correct (and identical to what a primary ray would compute).
        Vec3 o, d;
        ctx.camera.generateRay(x + 0.5f, y + 0.5f, o, d);
        if (vis.object[i] == kNoObject) {
          g.writeBackground(x, y, backgroundMotion(ctx, d));
          continue;
        }
        SurfaceSample s = resolveSurface(ctx.frame, int(vis.object[i]), int(vis.prim[i]), o, d);
        g.write(x, y, s, vis.depth[i], motionVector(ctx, s.object, s.position));
      }
  });
  ctx.passParts.push_back({"resolve", msSince(t1), 0});
}

}  // namespace tandem
