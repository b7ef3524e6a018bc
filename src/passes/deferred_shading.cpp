#include "passes/deferred_shading.h"

#include "pipeline/gbuffer_io.h"
#include "pipeline/view_tiles.h"
#include "shading/blinn_phong.h"

namespace tandem {

std::vector<BufferSlot> DeferredShadingPass::inputs() const {
  return gbufferSampleSlots();
}

void DeferredShadingPass::execute(FrameContext& ctx) {
  const GBufferReader g = gbufferSource(ctx, *this);
  Buffer& hdr = ctx.output(*this, "hdr");
  const Scene& scene = *ctx.scene;
  const ShadingContext shading = ShadingContext::from(scene);
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        Vec3 o, d;
        v.camera.generateRay(float(x - v.x) + 0.5f, float(y - v.y) + 0.5f, o, d);
        SurfaceSample s;
        Vec3 c = g.read(x, y, s) ? shadeBlinnPhong(s, -d, shading) : scene.skyRadiance(d);
        hdr.setRgb(x, y, c);
      }
  });
}

}  // namespace tandem
