#include "passes/common/whitted_settings.h"

#include <algorithm>

#include "passes/common/gpu_shadow_maps.h"
#include "passes/common/shadow_map_params.h"

namespace tandem {

const ParamTable<WhittedParams>& whittedTable() {
  using S = WhittedParams;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::maxDepth, {.name = "max_depth",
                              .min = 1,
                              .max = 64,
                              .doc = "maximum recursion depth of secondary rays"})
          .add(&S::importanceCutoff, {.name = "importance_cutoff",
                                      .min = 0,
                                      .max = 1,
                                      .doc = "stop recursing when a ray's weight falls below this"})
          .add(&S::shadowAttenuation,
               {.name = "shadow_attenuation",
                .doc = "occluder colour for Listing 8b: textured (as the G-buffer) or the base "
                       "material's",
                .choices = {"textured", "base"}})
          .add(
              &S::shadeAtMaxDepth,
              {.name = "shade_at_max_depth",
               .doc = "at max depth shade pure mirrors / clear glass with Blinn-Phong (Listing 8c: "
                      "0)"})
          .add(
              &S::shadows,
              {.name = "shadows",
               .doc = "shadows: classified (shadow maps decide where certain, rays the rest), rays "
                      "(every shadow traced) or maps (PCF shadow maps only)",
               .choices = {"classified", "rays", "maps"}})
          .add(
              &S::shadowCull,
              {.name = "shadow_cull",
               .min = 0,
               .max = 1,
               .doc = "no shadow query for a light below this fraction of the surface's unshadowed "
                      "light (0: only lights facing away or out of reach)"})
          .add(&S::shadowMapSize, shadowMapSizeParam())
          .add(&S::shadowMapFit, shadowMapFitParam());
  return table;
}

WhittedSettings WhittedParams::settings() const {
  WhittedSettings w;
  w.maxDepth = maxDepth;
  w.importanceCutoff = importanceCutoff;
  w.texturedShadows = shadowAttenuation == Attenuation::Textured;
  w.shadeAtMaxDepth = shadeAtMaxDepth;
  w.shadows = shadows;
  w.shadowCull = shadowCull;
  return w;
}

namespace {

// The shadow query counters' names under `pass`'s name.
struct ShadowQueryCounters {
  explicit ShadowQueryCounters(const Pass& pass) : key(pass.name() + "/") {}
  std::string key;
  std::string raysPerPixel() const { return key + "shadow_rays_per_pixel"; }
  std::string traced() const { return key + "shadow_traced"; }
  std::string culled() const { return key + "shadow_culled"; }
  std::string lit() const { return key + "shadow_lit"; }
  std::string shadowed() const { return key + "shadow_shadowed"; }
};

}  // namespace

std::vector<CounterDesc> whittedCounters(const Pass& pass) {
  const ShadowQueryCounters q(pass);
  return {{ShadowMapCounters::staticRedraws, "shadow maps redrawn for static geometry so far"},
          {ShadowMapCounters::movingRedraws, "shadow maps redrawn for moving geometry so far"},
          {ShadowMapCounters::mappedLights,
           "lights with shadow maps (the hybrid's: those reaching a surface in view so far)"},
          {q.raysPerPixel(), "shadow rays traced per shaded pixel"},
          {q.traced(), "share of light-surface pairs decided by a shadow ray"},
          {q.culled(), "share of pairs culled (negligible light)"},
          {q.lit(), "share of pairs the shadow maps classified as lit"},
          {q.shadowed(), "share of pairs the shadow maps classified as shadowed"}};
}

const ShadowMaps* shadowMapsFor(FrameContext& ctx, const Pass& pass, const WhittedParams& w,
                                const std::vector<uint8_t>* wanted, bool device) {
  if (w.shadows == ShadowMode::Rays) return nullptr;
  const ShadowMaps* maps = nullptr;
  const int size = ctx.shadowMapResolution(w.shadowMapSize, w.shadowMapFit);
  if (device) {
    maps = &deviceShadowMaps(ctx, pass, size, wanted);  // its part: the GPU's time
  } else {
    const auto t0 = Clock::now();
    maps = &ctx.shadowMaps(size, wanted);
    ctx.passParts.push_back({"shadow_maps", msSince(t0), 0});
  }
  reportShadowMaps(ctx, pass, *maps);
  return maps;
}

void reportShadowMaps(FrameContext& ctx, const Pass& pass, const ShadowMaps& maps) {
  ctx.report(pass, ShadowMapCounters::staticRedraws, maps.redraws());
  ctx.report(pass, ShadowMapCounters::movingRedraws, maps.movingRedraws());
  ctx.report(pass, ShadowMapCounters::mappedLights, maps.mappedLights());
}

WhittedFrame::WhittedFrame(FrameContext& ctx, const Pass& pass, const WhittedParams& p)
    : rt(ctx.rayTracer()),
      shading(ShadingContext::from(*ctx.scene)),
      whitted(rt, *ctx.scene, shading, p.settings()),
      raysBefore_(rt.raysTraced()) {
  whitted.countShadows(&tally);
  whitted.useShadowMaps(shadowMapsFor(ctx, pass, p));
}

void WhittedFrame::finish(FrameContext& ctx, const Pass& pass, double pixels) {
  reportShadows(ctx, pass, sum(tally), pixels);
  ctx.passRays += double(rt.raysTraced() - raysBefore_);
}

void reportShadows(FrameContext& ctx, const Pass& p, const ShadowCounts& c, double pixels) {
  const ShadowQueryCounters q(p);
  const double pairs = double(std::max<uint64_t>(c.pairs(), 1));
  ctx.report(p, q.raysPerPixel(), double(c.traced) / std::max(pixels, 1.0));
  ctx.report(p, q.traced(), double(c.traced) / pairs);
  ctx.report(p, q.culled(), double(c.culled) / pairs);
  ctx.report(p, q.lit(), double(c.lit) / pairs);
  ctx.report(p, q.shadowed(), double(c.shadowed) / pairs);
}

}  // namespace tandem
