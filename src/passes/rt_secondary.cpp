#include "passes/rt_secondary.h"

#include <tbb/combinable.h>

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
  in.push_back({"heuristic_mask", kEffectCount});
  return in;
}

namespace {
// Pixels and rays per object and effect, gathered per thread and summed once.
using EffectCounts = std::vector<std::array<uint64_t, 2 * kEffectCount>>;
}  // namespace

void RTSecondaryPass::execute(FrameContext& ctx) {
  const auto start = Clock::now();
  RayTracer& rt = ctx.rayTracer();
  const uint64_t raysBefore = rt.raysTraced();
  const Scene& scene = *ctx.scene;
  const size_t objects = scene.objects.size();
  const ShadingContext shading = ShadingContext::from(scene);
  Whitted whitted(rt, scene, shading, {int(param("max_depth")), float(param("importance_cutoff"))});
  GBufferReader g(ctx, *this);
  const Buffer& mask = ctx.input(bufferName("heuristic_mask"));
  Buffer& shadow = ctx.output(bufferName("shadow"), 3);
  Buffer& reflection = ctx.output(bufferName("reflection"), 3);
  Buffer& refraction = ctx.output(bufferName("refraction"), 3);
  tbb::combinable<EffectCounts> counts([&] { return EffectCounts(objects); });
  parallelTiles(ctx.width, ctx.height, [&](int x0, int y0, int x1, int y1) {
    std::vector<Vec3> vis(scene.lights.size());
    EffectCounts& count = counts.local();
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const float* m = mask.at(x, y);
        const bool want[kEffectCount] = {m[kShadow] > 0.5f, m[kReflection] > 0.5f,
                                         m[kRefraction] > 0.5f};
        SurfaceSample s;
        Vec3 shadowRgb(1.0f), reflectionRgb(0.0f), refractionRgb(0.0f);
        if ((want[0] || want[1] || want[2]) && g.read(x, y, s)) {
          auto& c = count[size_t(s.object)];
          Vec3 o, d;
          ctx.camera.generateRay(x + 0.5f, y + 0.5f, o, d);
          uint64_t r0 = rt.raysOnThisThread();
          if (want[kShadow]) {
            // Listing 8a: the shadow buffer starts at 1 and loses the light each occluder
            // blocks. One shading call weighted by (1 - visibility) sums exactly the blocked
            // light; subtracting the light-independent terms leaves only the lights' share.
            whitted.lightVisibility(s, vis.data());
            for (Vec3& v : vis) v = Vec3(1.0f) - v;
            Vec3 blocked = shadeBlinnPhong(s, -d, shading, vis.data()) -
                           (s.emission + shading.ambient * s.ambient);
            shadowRgb = Vec3(1.0f) - blocked;
            uint64_t r1 = rt.raysOnThisThread();
            c[kShadow] += 1;
            c[kEffectCount + kShadow] += r1 - r0;
            r0 = r1;
          }
          if (want[kReflection] && s.reflectivity > 0) {
            reflectionRgb = whitted.primaryReflection(s, d);
            uint64_t r1 = rt.raysOnThisThread();
            c[kReflection] += 1;
            c[kEffectCount + kReflection] += r1 - r0;
            r0 = r1;
          }
          if (want[kRefraction] && s.opacity < 1) {
            refractionRgb = whitted.primaryRefraction(s, d);
            c[kRefraction] += 1;
            c[kEffectCount + kRefraction] += rt.raysOnThisThread() - r0;
          }
        }
        shadow.setRgb(x, y, shadowRgb);
        reflection.setRgb(x, y, reflectionRgb);
        refraction.setRgb(x, y, refractionRgb);
      }
  });
  RtStats& stats = ctx.rtStats;
  stats.pixels.assign(objects, {});
  stats.rays.assign(objects, {});
  counts.combine_each([&](const EffectCounts& c) {
    for (size_t o = 0; o < objects; ++o)
      for (int e = 0; e < kEffectCount; ++e) {
        stats.pixels[o][size_t(e)] += c[o][size_t(e)];
        stats.rays[o][size_t(e)] += c[o][size_t(kEffectCount + e)];
      }
  });
  stats.serial = ctx.serial;
  stats.ms = msSince(start);
  ctx.passRays += double(rt.raysTraced() - raysBefore);
}

}  // namespace tandem
