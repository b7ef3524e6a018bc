// Small helpers shared by the depth-of-field passes (seed 000): clamping, the near/far split of
// a colour by its CoC, and the bokeh shape of the aperture (disk or regular n-gon) as a gather
// kernel sees it.
#pragma once
#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace tandem::dof {

constexpr float kZoneOfFocusCoc = 1.41421356f;  // √2 px: one sensor cell's diagonal (§3.3)

inline float saturate(float x) { return std::clamp(x, 0.0f, 1.0f); }
inline float smoothstep(float a, float b, float x) {
  const float t = saturate((x - a) / (b - a));
  return t * t * (3.0f - 2.0f * t);
}
inline float luma(Vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// Share of a sample that belongs to the near field, from its signed CoC: 1 well in front of the
// focus plane, 0 well behind, a linear ramp across the zone of focus (|CoC| < √2), so a surface
// crossing the focus plane moves smoothly from one field to the other (§3.2.2).
inline float nearShare(float coc) { return saturate(0.5f - coc / (2.0f * kZoneOfFocusCoc)); }

// The bokeh of an n-gon aperture (n >= 3, rotated `rotationDeg`) relative to a disk of the same
// circumradius: the polygon's extent in direction `angle` (radians, screen x right, y down) as a
// fraction of the circumradius, for a far-field spot (the lens shape seen upright: screen y is
// the lens's -up) or a near-field one (inverted through the centre). 1 for a disk.
inline float apertureExtent(int blades, float rotationDeg, float angle, bool nearField) {
  if (blades < 3) return 1.0f;
  // Screen direction -> lens-plane angle: y flips (screen down = lens -up); near field: + pi.
  float a = -angle + (nearField ? kPi : 0.0f) - radians(rotationDeg);
  const float sector = 2.0f * kPi / float(blades);
  a = a - sector * std::floor(a / sector);  // angle from the last corner, in [0, sector)
  return std::cos(0.5f * sector) / std::cos(a - 0.5f * sector);
}

}  // namespace tandem::dof
