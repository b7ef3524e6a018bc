#include "passes/vbuffer_shading.h"

#include "pipeline/view_tiles.h"
#include "shading/batch_shader.h"

namespace tandem {

void VBufferShadingPass::execute(FrameContext& ctx) {
  surfaces_.rasterize(ctx);
  const auto t1 = Clock::now();
  Buffer& hdr = ctx.output(*this, "hdr");
  Buffer* depth = ctx.outputIfConsumed(*this, "depth");
  Buffer* ids = ctx.outputIfConsumed(*this, "object_id");
  const Scene& scene = *ctx.scene;
  const ShadingContext shading = ShadingContext::from(scene);
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    const Camera& cam = v.camera;
    const bool perspective = cam.desc.projection == Projection::Perspective;
    VisibleSurfaces::TriangleCache cache;
    BatchShader shader(shading, hdr);
    surfaces_.resolveTile(
        ctx, v, x0, y0, x1, y1, cache,
        [&](int x, int y, const SurfaceSample& s, float d, Vec2) {
          if (depth) depth->at(x, y)[0] = d;
          if (ids) ids->at(x, y)[0] = float(s.object);
          // The surface lies on the pixel's camera ray: the eye direction needs no ray.
          shader.batch().set(shader.lane(), s,
                             perspective ? normalize(cam.eye - s.position) : -cam.forward);
          shader.push(x, y);
        },
        [&](int x, int y, Vec3) {
          Vec3 o, d;
          cam.generateRay(float(x - v.x) + 0.5f, float(y - v.y) + 0.5f, o, d);
          hdr.setRgb(x, y, scene.skyRadiance(d));
          if (depth) depth->at(x, y)[0] = 0.0f;
          if (ids) ids->at(x, y)[0] = -1.0f;
        });
  });
  ctx.passParts.push_back({"shading", msSince(t1), 0});
}

}  // namespace tandem
