#include "passes/deferred_shading.h"

#include "pipeline/gbuffer_io.h"
#include "pipeline/view_tiles.h"
#include "shading/shade_batch.h"

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
    const Camera& cam = v.camera;
    const bool perspective = cam.desc.projection == Projection::Perspective;
    ShadeBatch b;
    int xs[ShadeBatch::kMax];
    auto flush = [&](int y) {
      shadeBatch(b, shading);
      for (int k = 0; k < b.count; ++k) hdr.setRgb(xs[k], y, b.result(k));
      b.count = 0;
    };
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) {
        SurfaceSample s;
        if (!g.read(x, y, s)) {
          Vec3 o, d;
          cam.generateRay(float(x - v.x) + 0.5f, float(y - v.y) + 0.5f, o, d);
          hdr.setRgb(x, y, scene.skyRadiance(d));
          continue;
        }
        // The G-buffer point lies on the pixel's camera ray: the eye direction needs no ray.
        const Vec3 wo = perspective ? normalize(cam.eye - s.position) : -cam.forward;
        xs[b.count] = x;
        b.set(b.count++, s, wo);
        if (b.count == ShadeBatch::kMax) flush(y);
      }
      if (b.count) flush(y);
    }
  });
}

}  // namespace tandem
