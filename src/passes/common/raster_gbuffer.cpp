#include "passes/common/raster_gbuffer.h"

#include "pipeline/gbuffer_io.h"
#include "pipeline/gpu_gbuffer.h"
#include "pipeline/view_tiles.h"

namespace tandem {

std::vector<BufferSlot> RasterGBufferPass::outputs() const {
  return gbufferSlots();
}

void RasterGBufferPass::execute(FrameContext& ctx) {
  surfaces_.rasterize(ctx, *this);
  const auto t1 = Clock::now();
  GBufferView g = gbufferTargets(ctx, *this);
  writer_.beginFrame(ctx.frame);
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    writer_.tile(
        surfaces_, ctx, g, v, x0, y0, x1, y1, [](int, int, const SurfaceSample&, float) {},
        [](int, int, Vec3) {});
  });
  ctx.passParts.push_back({"resolve", msSince(t1), 0});
}

void RasterGBufferPass::executeGpu(FrameContext& ctx) {
  gpuSurfaces_.record(ctx, *this, gbufferDeviceTargets(ctx, *this), 0, "resolve",
                      settings().gpuRasterizer == RasterizerSettings::GpuRasterizer::Graphics);
}

}  // namespace tandem
