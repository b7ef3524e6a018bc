#include "passes/pt_reference.h"

#include "core/parallel.h"
#include "pipeline/frame_context.h"
#include "rt/path_tracer.h"

namespace tandem {

std::vector<ParamDesc> PTReferencePass::params() const {
  return {{"spp", ParamType::Int, 1024, 1, 1 << 20, "samples per pixel", {}},
          {"max_depth", ParamType::Int, 16, 1, 1024, "maximum path length in bounces", {}}};
}

void PTReferencePass::execute(FrameContext& ctx) {
  RayTracer& rt = ctx.rayTracer();
  const uint64_t before = rt.raysTraced();
  const Scene& scene = *ctx.scene;
  const ShadingContext shading = ShadingContext::from(scene);
  PathTracer pt(rt, scene, shading, {int(param("max_depth")), 3});
  const int spp = int(param("spp"));
  Buffer& hdr = ctx.output(bufferName("hdr"), 3);
  const uint64_t seed = ctx.seed * 0x9E3779B97F4A7C15ull + uint64_t(ctx.frameIndex);
  parallelTiles(ctx.width, ctx.height, [&](int x0, int y0, int x1, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        Pcg32 rng(seed, uint64_t(y) * uint64_t(ctx.width) + uint64_t(x));
        Vec3 sum(0.0f);
        for (int i = 0; i < spp; ++i) {
          Vec3 o, d;
          const float jx = rng.uniform(), jy = rng.uniform();
          ctx.camera.generateThinLensRay(x + jx, y + jy, rng.uniform(), rng.uniform(), o, d);
          Vec3 L = pt.radiance(o, d, rng);
          // A NaN or infinite sample (a degenerate pdf) must not poison the pixel.
          if (std::isfinite(L.x) && std::isfinite(L.y) && std::isfinite(L.z)) sum += L;
        }
        hdr.setRgb(x, y, sum / float(spp));
      }
  });
  ctx.passRays += double(rt.raysTraced() - before);
}

}  // namespace tandem
