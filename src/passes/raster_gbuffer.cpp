#include "passes/raster_gbuffer.h"

#include "pipeline/gbuffer_io.h"
#include "pipeline/view_tiles.h"
#include "shading/surface_resolve.h"

namespace tandem {

std::vector<BufferSlot> RasterGBufferPass::outputs() const {
  return gbufferSlots();
}

void RasterGBufferPass::execute(FrameContext& ctx) {
  auto t0 = Clock::now();
  visibility_.resize(ctx.views.size());
  stats_ = {};
  for (size_t i = 0; i < ctx.views.size(); ++i) {
    RasterStats s;
    rasterizer_.render(ctx.frame, ctx.views[i].camera, visibility_[i], &s);
    stats_.trianglesIn += s.trianglesIn;
    stats_.trianglesCulled += s.trianglesCulled;
    stats_.trianglesClipped += s.trianglesClipped;
    stats_.trianglesBinned += s.trianglesBinned;
  }
  ctx.counters["raster/triangles_in"] = double(stats_.trianglesIn);
  ctx.counters["raster/triangles_culled"] = double(stats_.trianglesCulled);
  ctx.counters["raster/triangles_clipped"] = double(stats_.trianglesClipped);
  ctx.counters["raster/triangles_binned"] = double(stats_.trianglesBinned);
  ctx.passParts.push_back({"visibility", msSince(t0), 0});
  auto t1 = Clock::now();
  GBufferView g = gbufferTargets(ctx, *this);
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    const VisibilityBuffer& vis = visibility_[size_t(&v - ctx.views.data())];
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const int lx = x - v.x, ly = y - v.y;
        size_t i = size_t(ly) * size_t(vis.width) + size_t(lx);
        // Barycentrics come from the pixel's camera ray against the visible triangle, which is
        // exact and perspective-correct (and identical to what a primary ray would compute).
        Vec3 o, d;
        v.camera.generateRay(float(lx) + 0.5f, float(ly) + 0.5f, o, d);
        if (vis.object[i] == kNoObject) {
          g.writeBackground(x, y, backgroundMotion(v, d));
          continue;
        }
        SurfaceSample s = resolveSurface(ctx.frame, int(vis.object[i]), int(vis.prim[i]), o, d);
        g.write(x, y, s, vis.depth[i], motionVector(ctx.frame, v, s.object, s.position));
      }
  });
  ctx.passParts.push_back({"resolve", msSince(t1), 0});
}

}  // namespace tandem
