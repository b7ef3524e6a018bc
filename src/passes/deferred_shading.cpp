#include "passes/deferred_shading.h"

#include "core/parallel.h"
#include "pipeline/frame_context.h"
#include "shading/blinn_phong.h"
#include "shading/gbuffer_sample.h"

namespace tandem {

std::vector<BufferSlot> DeferredShadingPass::inputs() const {
  return gbufferSampleSlots();
}

void DeferredShadingPass::execute(FrameContext& ctx) {
  GBufferReader g(ctx, *this);
  Buffer& hdr = ctx.output(bufferName("hdr"), 3);
  const Scene& scene = *ctx.scene;
  const ShadingContext shading = ShadingContext::from(scene);
  parallelTiles(ctx.width, ctx.height, [&](int x0, int y0, int x1, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        Vec3 o, d;
        ctx.camera.generateRay(x + 0.5f, y + 0.5f, o, d);
        SurfaceSample s;
        Vec3 c = g.read(x, y, s) ? shadeBlinnPhong(s, -d, shading) : scene.skyRadiance(d);
        hdr.setRgb(x, y, c);
      }
  });
}

}  // namespace tandem
