#include "passes/common/whitted_settings.h"

#include <algorithm>

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
          .add(&S::shadowMapSize, {.name = "shadow_map_size",
                                   .min = 64,
                                   .max = 8192,
                                   .doc = "shadow map resolution for classified and map shadows"});
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

const ShadowMaps* shadowMapsFor(FrameContext& ctx, const WhittedParams& w) {
  if (w.shadows == ShadowMode::Rays) return nullptr;
  const auto t0 = Clock::now();
  const ShadowMaps* maps = &ctx.shadowMaps(w.shadowMapSize);
  ctx.passParts.push_back({"shadow_maps", msSince(t0), 0});
  ctx.counters["shadow_maps/static_redraws"] = maps->redraws();
  ctx.counters["shadow_maps/moving_redraws"] = maps->movingRedraws();
  return maps;
}

WhittedFrame::WhittedFrame(FrameContext& ctx, const WhittedParams& p)
    : rt(ctx.rayTracer()),
      shading(ShadingContext::from(*ctx.scene)),
      whitted(rt, *ctx.scene, shading, p.settings()),
      raysBefore_(rt.raysTraced()) {
  whitted.countShadows(&tally);
  whitted.useShadowMaps(shadowMapsFor(ctx, p));
}

void WhittedFrame::finish(FrameContext& ctx, const Pass& pass, double pixels) {
  reportShadows(ctx, pass, sum(tally), pixels);
  ctx.passRays += double(rt.raysTraced() - raysBefore_);
}

void reportShadows(FrameContext& ctx, const Pass& p, const ShadowCounts& c, double pixels) {
  const std::string key = p.name() + "/";
  const double pairs = double(std::max<uint64_t>(c.pairs(), 1));
  ctx.counters[key + "shadow_rays_per_pixel"] = double(c.traced) / std::max(pixels, 1.0);
  ctx.counters[key + "shadow_traced"] = double(c.traced) / pairs;
  ctx.counters[key + "shadow_culled"] = double(c.culled) / pairs;
  ctx.counters[key + "shadow_lit"] = double(c.lit) / pairs;
  ctx.counters[key + "shadow_shadowed"] = double(c.shadowed) / pairs;
}

}  // namespace tandem
