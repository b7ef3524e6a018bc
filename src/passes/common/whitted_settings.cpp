#include "passes/common/whitted_settings.h"

#include <algorithm>

namespace tandem {

std::vector<ParamDesc> whittedParams(ShadowMode shadows) {
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
           {}},
          {"shadows",
           ParamType::Enum,
           double(int(shadows)),
           0,
           2,
           "shadows: classified (shadow maps decide where certain, rays the rest), rays (every "
           "shadow traced) or maps (PCF shadow maps only)",
           {"classified", "rays", "maps"}},
          {"shadow_cull",
           ParamType::Float,
           0.004,
           0,
           1,
           "no shadow query for a light below this fraction of the surface's unshadowed light "
           "(0: only lights facing away or out of reach)",
           {}},
          {"shadow_map_size",
           ParamType::Int,
           1024,
           64,
           8192,
           "shadow map resolution for classified and map shadows",
           {}}};
}

WhittedSettings whittedSettings(const Pass& p) {
  WhittedSettings w;
  w.maxDepth = int(p.param("max_depth"));
  w.importanceCutoff = float(p.param("importance_cutoff"));
  w.texturedShadows = p.param("shadow_attenuation") == 0;
  w.shadeAtMaxDepth = p.param("shade_at_max_depth") != 0;
  w.shadows = ShadowMode(int(p.param("shadows")));
  w.shadowCull = float(p.param("shadow_cull"));
  return w;
}

const ShadowMaps* shadowMapsFor(FrameContext& ctx, const Pass& p) {
  if (ShadowMode(int(p.param("shadows"))) == ShadowMode::Rays) return nullptr;
  const auto t0 = Clock::now();
  const ShadowMaps* maps = &ctx.shadowMaps(int(p.param("shadow_map_size")));
  ctx.passParts.push_back({"shadow_maps", msSince(t0), 0});
  ctx.counters["shadow_maps/static_redraws"] = maps->redraws();
  ctx.counters["shadow_maps/moving_redraws"] = maps->movingRedraws();
  return maps;
}

void prepareShadows(FrameContext& ctx, const Pass& p, Whitted& w, ShadowTally* tally) {
  w.countShadows(tally);
  w.useShadowMaps(shadowMapsFor(ctx, p));
}

void reportShadows(FrameContext& ctx, const Pass& p, const ShadowCounts& c, double pixels) {
  const std::string key = (p.label.empty() ? p.type() : p.label) + "/";
  const double pairs = double(std::max<uint64_t>(c.pairs(), 1));
  ctx.counters[key + "shadow_rays_per_pixel"] = double(c.traced) / std::max(pixels, 1.0);
  ctx.counters[key + "shadow_traced"] = double(c.traced) / pairs;
  ctx.counters[key + "shadow_culled"] = double(c.culled) / pairs;
  ctx.counters[key + "shadow_lit"] = double(c.lit) / pairs;
  ctx.counters[key + "shadow_shadowed"] = double(c.shadowed) / pairs;
}

}  // namespace tandem
