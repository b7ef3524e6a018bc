// postfx_dof's sampling patterns, shared by its CPU and GPU versions so both take the same taps:
// the 81-tap gather's rings (turned by a per-frame angle) with the aperture polygon's extent
// along each, and the 9-tap prefilter's directions.
#pragma once
#include <array>
#include <cstdint>

#include "scene/thin_lens.h"

namespace tandem::dof {

constexpr int kGatherTaps = 81;
constexpr int kPostfxTile = 8;  // half-res pixels per tile side (16 frame pixels)

// A tap of the unit kernel: offset and distance from the centre.
struct Tap {
  float x, y, dist;
};

// The centre, then rings k = 1..4 of 8k taps at radius k/4, turned by a new angle every
// executed frame (`serial`; a static shot repeats its frame index); and the polygon's extent in
// the direction from each tap to the centre, for far- and near-field spots (1: a disk, or
// `polygon` off).
struct GatherTaps {
  std::array<Tap, kGatherTaps> taps;
  std::array<float, kGatherTaps> extentFar, extentNear;
};
GatherTaps gatherTaps(const ThinLens& lens, bool polygon, int64_t serial);

// The prefilter's tap t (0..7) direction: cos and sin of 2πt/8.
void prefilterDirection(int t, float& cosA, float& sinA);

}  // namespace tandem::dof
