#include "passes/rt_secondary.h"

#include <tbb/combinable.h>

#include "core/cycle_clock.h"
#include "passes/rt_stats.h"
#include "pipeline/gbuffer_io.h"
#include "pipeline/view_tiles.h"
#include "rt/whitted.h"

namespace tandem {

std::vector<ParamDesc> whittedParams() {
  return {{"max_depth", ParamType::Int, 10, 1, 64, "maximum recursion depth of secondary rays", {}},
          {"importance_cutoff",
           ParamType::Float,
           0.01,
           0,
           1,
           "stop recursing when a ray's weight falls below this",
           {}},
          {"shadow_attenuation",
           ParamType::Enum,
           0,
           0,
           1,
           "occluder colour for Listing 8b: textured (as the G-buffer) or the base material's",
           {"textured", "base"}},
          {"shade_at_max_depth",
           ParamType::Bool,
           0,
           0,
           1,
           "at max depth shade pure mirrors / clear glass with Blinn-Phong (Listing 8c: 0)",
           {}}};
}

WhittedSettings whittedSettings(const Pass& p) {
  WhittedSettings w;
  w.maxDepth = int(p.param("max_depth"));
  w.importanceCutoff = float(p.param("importance_cutoff"));
  w.texturedShadows = p.param("shadow_attenuation") == 0;
  w.shadeAtMaxDepth = p.param("shade_at_max_depth") != 0;
  return w;
}

std::vector<ParamDesc> RTSecondaryPass::params() const {
  std::vector<ParamDesc> p = whittedParams();
  p.push_back({"outside_mask_shadow",
               ParamType::Float,
               0,
               0,
               1,
               "shadow value outside the mask (Listing 8a: 0; 1 is neutral)",
               {}});
  return p;
}

std::vector<BufferSlot> RTSecondaryPass::inputs() const {
  std::vector<BufferSlot> in = gbufferSampleSlots();
  in.push_back({"heuristic_mask", kEffectCount, BufferKind::Mask});
  in.push_back({"rt_request", 1, BufferKind::Mask, Extent::fixed(1, 1), false, true});
  return in;
}

std::vector<BufferSlot> RTSecondaryPass::outputs() const {
  return {{"shadow", 3}, {"reflection", 3}, {"refraction", 3}, rtStatsSlot(false)};
}

namespace {
// Per worker thread and object: pixels, rays and time-stamp ticks of each effect.
struct EffectTally {
  std::array<uint64_t, kEffectCount> pixels{}, rays{}, ticks{};
};
using EffectTallies = std::vector<EffectTally>;
}  // namespace

void RTSecondaryPass::execute(FrameContext& ctx) {
  const auto start = Clock::now();
  const TickRate tickRate;
  RayTracer& rt = ctx.rayTracer();
  const uint64_t raysBefore = rt.raysTraced();
  const Scene& scene = *ctx.scene;
  const size_t objects = scene.objects.size();
  const ShadingContext shading = ShadingContext::from(scene);
  Whitted whitted(rt, scene, shading, whittedSettings(*this));
  const GBufferReader g = gbufferSource(ctx, *this);
  const Buffer& mask = ctx.input(*this, "heuristic_mask");
  Buffer& shadow = ctx.output(*this, "shadow");
  Buffer& reflection = ctx.output(*this, "reflection");
  Buffer& refraction = ctx.output(*this, "refraction");
  const Buffer* request = ctx.optionalInput(*this, "rt_request");
  const bool timed = request && request->data[0] > 0.5f;
  const float outsideShadow = float(param("outside_mask_shadow"));
  tbb::combinable<EffectTallies> tallies([&] { return EffectTallies(objects); });
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    std::vector<Vec3> vis(scene.lights.size());
    EffectTallies& tally = tallies.local();
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const float* m = mask.at(x, y);
        const bool want[kEffectCount] = {m[kShadow] > 0.5f, m[kReflection] > 0.5f,
                                         m[kRefraction] > 0.5f};
        SurfaceSample s;
        // Listing 8a: 0 in all three outside the mask (`outside_mask_shadow` = 1 keeps the
        // shadow buffer neutral there instead; blend never reads it outside the mask).
        Vec3 shadowRgb(outsideShadow), reflectionRgb(0.0f), refractionRgb(0.0f);
        if ((want[0] || want[1] || want[2]) && g.read(x, y, s)) {
          shadowRgb = Vec3(1.0f);
          EffectTally& t = tally[size_t(s.object)];
          Vec3 o, d;
          v.camera.generateRay(float(x - v.x) + 0.5f, float(y - v.y) + 0.5f, o, d);
          // What each effect costs this object, in rays and in time (the heuristic's ms budget
          // and recursion-aware costs are built from these).
          uint64_t r0 = rt.raysOnThisThread(), c0 = timed ? cycleNow() : 0;
          auto account = [&](int e) {
            uint64_t r1 = rt.raysOnThisThread(), c1 = timed ? cycleNow() : 0;
            t.pixels[size_t(e)] += 1;
            t.rays[size_t(e)] += r1 - r0;
            t.ticks[size_t(e)] += c1 - c0;
            r0 = r1;
            c0 = c1;
          };
          if (want[kShadow]) {
            // Listing 8a: the shadow buffer starts at 1 and loses the light each occluder
            // blocks. One shading call weighted by (1 - visibility) sums exactly the blocked
            // light; subtracting the light-independent terms leaves only the lights' share.
            whitted.lightVisibility(s, vis.data());
            for (Vec3& v : vis) v = Vec3(1.0f) - v;
            Vec3 blocked = shadeBlinnPhong(s, -d, shading, vis.data()) -
                           (s.emission + shading.ambient * s.ambient);
            shadowRgb = Vec3(1.0f) - blocked;
            account(kShadow);
          }
          if (want[kReflection] && s.reflectivity > 0) {
            reflectionRgb = whitted.primaryReflection(s, d);
            account(kReflection);
          }
          if (want[kRefraction] && s.opacity < 1) {
            refractionRgb = whitted.primaryRefraction(s, d);
            account(kRefraction);
          }
        }
        shadow.setRgb(x, y, shadowRgb);
        reflection.setRgb(x, y, reflectionRgb);
        refraction.setRgb(x, y, refractionRgb);
      }
  });
  RtStats stats;
  stats.timeEffects = timed;
  stats.pixels.assign(objects, {});
  stats.rays.assign(objects, {});
  stats.cpuMs.assign(objects, {});
  const double msPerTick = 1.0 / tickRate.ticksPerMs();
  tallies.combine_each([&](const EffectTallies& tally) {
    for (size_t o = 0; o < objects; ++o)
      for (size_t e = 0; e < size_t(kEffectCount); ++e) {
        stats.pixels[o][e] += tally[o].pixels[e];
        stats.rays[o][e] += tally[o].rays[e];
        stats.cpuMs[o][e] += double(tally[o].ticks[e]) * msPerTick;
      }
  });
  stats.ms = msSince(start);
  writeRtStats(stats, ctx.output(*this, "rt_stats", int(objects) + 1, 1));
  ctx.passRays += double(rt.raysTraced() - raysBefore);
}

}  // namespace tandem
