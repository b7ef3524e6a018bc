#include "passes/interleaved/interleaved_raster.h"

#include <algorithm>

#include "pipeline/frame_context.h"

namespace tandem {

std::vector<CounterDesc> InterleavedRasterPass::counters() const {
  using C = InterleavedRasterCounters;
  std::vector<CounterDesc> all = InterleavedPass::counters();
  all.insert(all.end(), {{C::setUpPerPass, "triangles set up per (time, lens) pass"},
                         {C::setUpMax, "most triangles set up by one pass"},
                         {C::setUpMin, "fewest triangles set up by one pass"},
                         {C::staticSetUpOnce, "static triangles set up once for all passes"}});
  return all;
}

void InterleavedRasterPass::visibility(FrameContext& ctx, const SampleLayout& layout,
                                       const std::vector<Camera>& cams,
                                       const std::vector<float>& taus, const uint8_t* active,
                                       VisibilityBuffer& vis) {
  // A masked pass draws only the cells (tiles) that hold a needed sample.
  const TileShape& shape = layout.shape;
  if (active) {
    cellActive_.assign(size_t(layout.cells()), 0);
    const int SW = layout.stridesW(), cellSW = shape.tw * shape.sx, cellSH = shape.th * shape.sy;
    for (int y = 0; y < layout.stridesH(); ++y)
      for (int x = 0; x < SW; ++x)
        if (active[size_t(y) * size_t(SW) + size_t(x)])
          cellActive_[size_t(y / cellSH) * size_t(layout.cellsX) + size_t(x / cellSW)] = 1;
  }
  auto masked = [&](Rasterizer::SampleSet set) {
    set.cellActive = active ? cellActive_.data() : nullptr;
    return set;
  };
  // Every sample: a pass costs its triangles' setup, not its samples.
  // When no pair moves the camera (no lens, no camera motion in the shutter), geometry that
  // stands still looks the same at every pair: it is rasterized once into every sample, and
  // only the moving objects once per pair, over it.
  const bool moving = ctx.frame.motionBlur();
  bool sameView = true;
  for (const Camera& c : cams) sameView = sameView && sameMatrix(c.viewProj, cams.front().viewProj);
  std::vector<uint8_t> movers(ctx.frame.objects.size(), 0), still(movers.size(), 0);
  size_t moverCount = 0;
  for (size_t o = 0; o < movers.size(); ++o) {
    movers[o] = !ctx.frame.objects[o].stepPositions.empty();
    still[o] = !movers[o];
    moverCount += movers[o];
  }
  const bool shareStatic = sameView && cams.size() > 1;
  double setUp = 0, setUpMax = 0, setUpMin = 1e300, shared = 0;
  if (shareStatic) {
    RasterStats stats;
    rasterizer_.renderSamples(ctx.frame, cams.front(), masked(layout.allSamples()), vis,
                              Rasterizer::Subset{&still, false}, &stats,
                              moving ? taus.front() : -1.0f);
    shared = double(stats.trianglesBinned);
  }
  for (size_t j = 0; j < cams.size(); ++j) {
    if (shareStatic && moverCount == 0) break;
    RasterStats stats;
    const Rasterizer::Subset subset =
        shareStatic ? Rasterizer::Subset{&movers, true} : Rasterizer::Subset{};
    rasterizer_.renderSamples(ctx.frame, cams[j], masked(layout.passSamples(int(j))), vis, subset,
                              &stats, moving ? taus[j] : -1.0f);
    setUp += double(stats.trianglesBinned);
    setUpMax = std::max(setUpMax, double(stats.trianglesBinned));
    setUpMin = std::min(setUpMin, double(stats.trianglesBinned));
  }
  using C = InterleavedRasterCounters;
  ctx.report(*this, C::setUpPerPass, setUp / double(cams.size()));
  ctx.report(*this, C::setUpMax, setUpMax);
  ctx.report(*this, C::setUpMin, std::min(setUpMin, setUpMax));
  ctx.report(*this, C::staticSetUpOnce, shared);
}

}  // namespace tandem
