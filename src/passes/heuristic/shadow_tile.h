// Classified shadows of one screen tile for rt_secondary, in structure-of-arrays form: the
// tile's shadow pixels are read from the G-buffer 16 lanes at a time, each light's share of
// their light weighed in one shading call, the lanes classified by the frame's shadow maps, the
// undecided ones traced as 8-wide packets per light, and S (Listing 8a: 1 - the light the
// occluders block) shaded only for lights that something blocks.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/buffer.h"
#include "passes/heuristic/rt_feedback.h"
#include "rt/whitted.h"
#include "scene/view.h"
#include "shading/gbuffer_sample.h"

namespace tandem {

// What one worker thread spent on one object's effects: pixels, rays and time-stamp ticks.
struct EffectTally {
  std::array<uint64_t, kEffectCount> pixels{}, rays{}, ticks{};
};

struct ShadowTile {
  const GBufferReader& g;
  const Buffer* mask;  // null: every surface pixel (deferred shading with map shadows)
  const Buffer &ids, &geoNormal;
  const Scene& scene;
  const ShadingContext& shading;
  const RayTracer* rt;     // null with settings.shadows = Maps (nothing is traced)
  const ShadowMaps* maps;  // null: every shadow that culling leaves is traced
  const WhittedSettings& settings;
  Buffer& shadow;
  Buffer* classes;      // optional: traced, lit, shadowed shares per pixel (rt_secondary's AOV)
  int classLight;       // the light `classes` shows, -1 all
  bool timed;           // count ticks per object
  const Buffer* order;  // heuristic_order: which node rank each pixel's shadow belongs to
  // ss_fallback: the pixels whose shadow the mask leaves out, S written at `shadowChannel` of
  // `shadow` and 1 at `coverChannel` (>= 0) where it was.
  bool unselected = false;
  int shadowChannel = 0, coverChannel = -1;
  // deferred_shading with map shadows: the shaded radiance with S applied, L - (1 - S) (eq. 4, as
  // blend would take it), written at `shadowChannel` instead of S.
  bool shadedRadiance = false;
};

// (traced, lit, shadowed) shares of lane j's lights that reach it (classes of 8-bit ShadowClass
// at [stride * light + lane]), or of light `only` alone when it is >= 0.
Vec3 classShares(const uint8_t* classes, size_t lights, size_t stride, int j, int only);

// Writes S for the pixels of [x0, x1) x [y0, y1) in view v whose heuristic mask selects shadows
// (every one without a mask; of node rank `rank` only, when >= 0: a deadline's work item) and
// that show a surface; counts
// into tally (per object) and counts.
void classifiedShadowTile(const ShadowTile& t, const View& v, int x0, int y0, int x1, int y1,
                          int64_t rank, EffectTally* tally, ShadowCounts& counts);

}  // namespace tandem
