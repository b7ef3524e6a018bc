#include "passes/raster_gbuffer.h"

#include "pipeline/gbuffer_io.h"
#include "pipeline/view_tiles.h"

namespace tandem {

std::vector<BufferSlot> RasterGBufferPass::outputs() const {
  return gbufferSlots();
}

void RasterGBufferPass::execute(FrameContext& ctx) {
  surfaces_.rasterize(ctx);
  const auto t1 = Clock::now();
  GBufferView g = gbufferTargets(ctx, *this);
  const FrameScene& fs = ctx.frame;
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    VisibleSurfaces::TriangleCache cache;
    surfaces_.resolveTile(
        ctx, v, x0, y0, x1, y1, cache,
        [&](int x, int y, const SurfaceSample& s, float depth, Vec2 pixel) {
          g.write(x, y, s, depth, motionVectorAtPixel(fs, v, s.object, s.position, pixel));
        },
        [&](int x, int y, Vec3 d) { g.writeBackground(x, y, backgroundMotion(v, normalize(d))); });
  });
  ctx.passParts.push_back({"resolve", msSince(t1), 0});
}

}  // namespace tandem
