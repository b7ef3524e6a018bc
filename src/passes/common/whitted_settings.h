// The parameters every pass that traces Whitted rays shares (recursion, Listing 8b's occluder
// colour, the shadow mode and culling), the settings they give, and the frame's shadow maps and
// counters behind classified shadows.
#pragma once
#include <string>

#include "pipeline/frame_context.h"
#include "pipeline/param_table.h"
#include "rt/whitted.h"

namespace tandem {

// Nested into each tracing pass's settings (ParamTable::nest). A pass's own initialiser may
// change a default: rt_whitted, the all-rays baseline, defaults `shadows` to rays.
struct WhittedParams {
  enum class Attenuation { Textured, Base };
  int maxDepth = 10;
  float importanceCutoff = 0.01f;
  Attenuation shadowAttenuation = Attenuation::Textured;
  bool shadeAtMaxDepth = false;
  ShadowMode shadows = ShadowMode::Classified;
  float shadowCull = 0.004f;
  int shadowMapSize = 1024;
  bool shadowMapFit = false;  // FrameContext::shadowMapResolution
  WhittedSettings settings() const;
};
const ParamTable<WhittedParams>& whittedTable();

// The counters of the frame's shadow maps, reported by the pass that brings them up to date.
struct ShadowMapCounters {
  static constexpr const char* staticRedraws = "shadow_maps/static_redraws";
  static constexpr const char* movingRedraws = "shadow_maps/moving_redraws";
  static constexpr const char* mappedLights = "shadow_maps/mapped_lights";
};

// What a pass that shades with Whitted rays reports (its Pass::counters() includes these): the
// shadow maps' redraws and its shadow queries ("<name>/shadow_traced", ...; reportShadows).
std::vector<CounterDesc> whittedCounters(const Pass& pass);

// The frame's shadow maps when `w` uses them (drawn or brought up to date here; a pass part
// "shadow_maps" times that, `pass` reports their counters), else null. `wanted`: the lights
// that need maps (lightsInView; null: all). `device`: the GPU's maps, their drawing recorded
// into the current submission (gpu_shadow_maps.h).
const ShadowMaps* shadowMapsFor(FrameContext& ctx, const Pass& pass, const WhittedParams& w,
                                const std::vector<uint8_t>* wanted = nullptr, bool device = false);
// The counters of the maps `pass` used this frame.
void reportShadowMaps(FrameContext& ctx, const Pass& pass, const ShadowMaps& maps);

// One frame of a pass that shades with Whitted rays: the shading context, the tracer with the
// pass's settings and the frame's shadow maps, and the tally of its shadow queries. finish()
// reports the shadow counters and every ray the pass traced (primary rays included).
class WhittedFrame {
 public:
  WhittedFrame(FrameContext& ctx, const Pass& pass, const WhittedParams& p);
  WhittedFrame(const WhittedFrame&) = delete;  // the tracer points at the shading context
  WhittedFrame& operator=(const WhittedFrame&) = delete;
  // `pixels`: the pass's shaded pixels (the shadow counters are shares per pixel).
  void finish(FrameContext& ctx, const Pass& pass, double pixels);

  RayTracer& rt;
  const ShadingContext shading;
  Whitted whitted;
  ShadowTally tally;

 private:
  uint64_t raysBefore_;
};

// Counters of one pass's shadow queries ("<label>/shadow_rays_per_pixel", "/shadow_traced",
// "/shadow_culled": shares of the light-surface pairs; pixels: the pass's shaded pixels).
void reportShadows(FrameContext& ctx, const Pass& p, const ShadowCounts& c, double pixels);

}  // namespace tandem
