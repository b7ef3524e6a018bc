#include "passes/rt_secondary.h"

#include "core/parallel.h"
#include "pipeline/frame_context.h"
#include "rt/whitted.h"
#include "shading/gbuffer_sample.h"

namespace tandem {

std::vector<ParamDesc> whittedParams() {
  return {{"max_depth", ParamType::Int, 10, 1, 64, "maximum recursion depth of secondary rays", {}},
          {"importance_cutoff",
           ParamType::Float,
           0.01,
           0,
           1,
           "stop recursing when a ray's weight falls below this",
           {}}};
}

std::vector<BufferSlot> RTSecondaryPass::inputs() const {
  std::vector<BufferSlot> in = gbufferSampleSlots();
  in.push_back({"heuristic_mask", 1});
  return in;
}

void RTSecondaryPass::execute(FrameContext& ctx) {
  RayTracer& rt = ctx.rayTracer();
  const uint64_t raysBefore = rt.raysTraced();
  const Scene& scene = *ctx.scene;
  const ShadingContext shading = ShadingContext::from(scene);
  Whitted whitted(rt, scene, shading, {int(param("max_depth")), float(param("importance_cutoff"))});
  GBufferReader g(ctx, *this);
  const Buffer& mask = ctx.input(bufferName("heuristic_mask"));
  Buffer& shadow = ctx.output(bufferName("shadow"), 3);
  Buffer& reflection = ctx.output(bufferName("reflection"), 3);
  Buffer& refraction = ctx.output(bufferName("refraction"), 3);
  parallelTiles(ctx.width, ctx.height, [&](int x0, int y0, int x1, int y1) {
    std::vector<Vec3> vis(scene.lights.size());
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        SurfaceSample s;
        if (mask.at(x, y)[0] < 1e-4f || !g.read(x, y, s)) {
          shadow.setRgb(x, y, Vec3(1.0f));
          reflection.setRgb(x, y, Vec3(0.0f));
          refraction.setRgb(x, y, Vec3(0.0f));
          continue;
        }
        Vec3 o, d;
        ctx.camera.generateRay(x + 0.5f, y + 0.5f, o, d);
        // Listing 8a: the shadow buffer starts at 1 and loses the light each occluder blocks.
        // One shading call weighted by (1 - visibility) sums exactly the light that is blocked;
        // subtracting the light-independent terms leaves only the lights' share.
        whitted.lightVisibility(s, vis.data());
        for (Vec3& v : vis) v = Vec3(1.0f) - v;
        Vec3 blocked = shadeBlinnPhong(s, -d, shading, vis.data()) -
                       (s.emission + shading.ambient * s.ambient);
        shadow.setRgb(x, y, Vec3(1.0f) - blocked);
        reflection.setRgb(x, y, whitted.primaryReflection(s, d));
        refraction.setRgb(x, y, whitted.primaryRefraction(s, d));
      }
  });
  ctx.passRays += double(rt.raysTraced() - raysBefore);
}

}  // namespace tandem
