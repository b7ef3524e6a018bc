#include "passes/common/visible_surfaces.h"

namespace tandem {

std::vector<CounterDesc> RasterCounters::all() {
  return {{trianglesIn, "triangles submitted to the rasterizer, all views"},
          {trianglesCulled, "triangles culled (back-facing, outside the frustum, too small)"},
          {trianglesClipped, "triangles clipped against the near plane"},
          {trianglesBinned, "triangles binned into tiles"}};
}

void VisibleSurfaces::rasterize(FrameContext& ctx, const Pass& pass) {
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
  ctx.report(pass, RasterCounters::trianglesIn, double(total.trianglesIn));
  ctx.report(pass, RasterCounters::trianglesCulled, double(total.trianglesCulled));
  ctx.report(pass, RasterCounters::trianglesClipped, double(total.trianglesClipped));
  ctx.report(pass, RasterCounters::trianglesBinned, double(total.trianglesBinned));
  ctx.passParts.push_back({"visibility", msSince(t0), 0});
}

}  // namespace tandem
