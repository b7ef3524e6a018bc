#include "passes/common/visible_surfaces.h"

namespace tandem {

void VisibleSurfaces::rasterize(FrameContext& ctx) {
  const auto t0 = Clock::now();
  visibility_.resize(ctx.views.size());
  RasterStats total;
  for (size_t i = 0; i < ctx.views.size(); ++i) {
    RasterStats s;
    rasterizer_.render(ctx.frame, ctx.views[i].jitteredCamera, visibility_[i], &s);
    total.trianglesIn += s.trianglesIn;
    total.trianglesCulled += s.trianglesCulled;
    total.trianglesClipped += s.trianglesClipped;
    total.trianglesBinned += s.trianglesBinned;
  }
  ctx.counters["raster/triangles_in"] = double(total.trianglesIn);
  ctx.counters["raster/triangles_culled"] = double(total.trianglesCulled);
  ctx.counters["raster/triangles_clipped"] = double(total.trianglesClipped);
  ctx.counters["raster/triangles_binned"] = double(total.trianglesBinned);
  ctx.passParts.push_back({"visibility", msSince(t0), 0});
}

}  // namespace tandem
