// The parameters every pass that traces Whitted rays shares (recursion, Listing 8b's occluder
// colour, the shadow mode and culling), the settings they give, and the frame's shadow maps and
// counters behind classified shadows.
#pragma once
#include <string>
#include <vector>

#include "pipeline/frame_context.h"
#include "pipeline/pass.h"
#include "rt/whitted.h"

namespace tandem {

// `shadows`: the default of the shadow mode (classified for the hybrids; rt_whitted, the
// all-rays baseline, traces every shadow).
std::vector<ParamDesc> whittedParams(ShadowMode shadows = ShadowMode::Classified);
WhittedSettings whittedSettings(const Pass& p);

// The frame's shadow maps when p's settings use them (drawn or brought up to date here; a pass
// part "shadow_maps" times that), else null.
const ShadowMaps* shadowMapsFor(FrameContext& ctx, const Pass& p);
// Hands `w` those maps and the tally to count its shadow queries into.
void prepareShadows(FrameContext& ctx, const Pass& p, Whitted& w, ShadowTally* tally);

// Counters of one pass's shadow queries ("<label>/shadow_rays_per_pixel", "/shadow_traced",
// "/shadow_culled": shares of the light-surface pairs; pixels: the pass's shaded pixels).
void reportShadows(FrameContext& ctx, const Pass& p, const ShadowCounts& c, double pixels);

}  // namespace tandem
