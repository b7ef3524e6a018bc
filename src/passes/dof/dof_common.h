// Small helpers shared by the depth-of-field passes (Tan et al. 2022): clamping, the near/far split
// of a colour by its CoC, and the bokeh shape of the aperture (disk or regular n-gon) as a gather
// kernel sees it.
#pragma once
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/math.h"
#include "pipeline/pass.h"

namespace tandem::dof {

constexpr float kZoneOfFocusCoc = 1.41421356f;  // √2 px: one sensor cell's diagonal (§3.3)

// The channels of the accumulated ray-traced DoF (rt_color, rt_recon): the merged colour, its
// CoC (frame pixels), the hit ratio, the coverage (1 where any ray has contributed; bilinear
// samples divide by it) and the near field's own colour.
struct RtChannels {
  static constexpr int kRgb = 0, kCoc = 3, kHit = 4, kCoverage = 5, kNear = 6, kCount = 9;
  static BufferSlot slot(std::string name) {
    return BufferSlot{std::move(name), 0, BufferKind::Color, Extent::any()}.named(
        {"r", "g", "b", "coc", "hit", "coverage", "near_r", "near_g", "near_b"});
  }
};

// The channels rt_dof writes and dof_accumulation reads: rt_near and rt_far hold a layer's mean
// colour and CoC; rt_hit the near share of the pixel's rays and how many there were;
// rt_far_position the mean far hit and whether any ray hit the far field.
constexpr int kLayerCoc = 3, kLayerChannels = 4;
inline BufferSlot layerSlot(std::string name) {
  return BufferSlot{std::move(name), 0, BufferKind::Color, Extent::any()}.named(
      {"r", "g", "b", "coc"});
}
constexpr int kHitNearShare = 0, kHitRays = 1, kHitChannels = 2;
inline BufferSlot hitSlot() {
  return BufferSlot{"rt_hit", 0, BufferKind::Mask, Extent::any()}.named({"near_share", "rays"});
}
constexpr int kFarPositionValid = 3, kFarPositionChannels = 4;
inline BufferSlot farPositionSlot() {
  return BufferSlot{"rt_far_position", 0, BufferKind::Position, Extent::any()}.named(
      {"x", "y", "z", "valid"});
}
// dof_accumulation's histories: acc_near and acc_far hold a layer's colour and CoC premultiplied
// by its share of the rays, and that share; acc_moments the temporal moments of the merged
// luminance and the frames they average.
struct AccChannels {
  static constexpr int kRgb = 0, kShare = 3, kCoc = 4, kCount = 5;
  static BufferSlot slot(std::string name) {
    return BufferSlot{std::move(name), 0, BufferKind::Color, Extent::any()}.named(
        {"r", "g", "b", "share", "coc"});
  }
};
struct MomentChannels {
  static constexpr int kMean = 0, kMeanSquare = 1, kFrames = 2, kCount = 3;
  static BufferSlot slot() {
    return BufferSlot{"acc_moments", 0, BufferKind::List, Extent::any()}.named(
        {"mean", "mean_square", "frames"});
  }
};
// The channels of postfx_dof's bokeh buffer: the bokeh intensity (the share of reaching taps
// that are highlights) and the share of the gather's weight from foreground taps.
struct BokehChannels {
  static constexpr int kIntensity = 0, kForeground = 1, kCount = 2;
  static BufferSlot slot() {
    return BufferSlot{"bokeh", 0, BufferKind::Mask}.named({"intensity", "foreground"});
  }
};

// `fine_coc`, declared by dof_composite (below this |CoC| in frame pixels it gathers the sharp
// image at full resolution) and by ray_mask (which then traces no rays there): one range and
// default, so the two stay set alike unless a pipeline sets them apart.
constexpr float kFineCocDefault = 12;
inline ParamDesc fineCocParam(std::string doc) {
  return {.name = "fine_coc", .min = 0, .max = 64, .doc = std::move(doc)};
}

// A hit ratio or foreground share below this is no silhouette (the noise floor of a few rays).
constexpr float kSilhouette = 0.02f;

// Three consecutive channels from `offset` of a pixel (an rgb or xyz group) as a vector.
inline Vec3 rgbAt(const float* pixel, int offset) {
  return Vec3(pixel[offset], pixel[offset + 1], pixel[offset + 2]);
}

inline float saturate(float x) {
  return std::clamp(x, 0.0f, 1.0f);
}
inline float smoothstep(float a, float b, float x) {
  const float t = saturate((x - a) / (b - a));
  return t * t * (3.0f - 2.0f * t);
}

// Share of a sample that belongs to the near field, from its signed CoC (§3.2.2 splits by the
// distance to the focus plane, smoothly): 0 behind the focus plane and inside the zone of focus,
// 1 from a CoC of −2√2 on, a linear ramp between. Everything sharp counts as far field, so the
// hit ratio (the near share of a pixel's rays) is exactly what a blurred foreground covers of
// it — 0 over an in-focus background that no foreground reaches; sharp points gain nothing from
// the near field's motion-vector reprojection anyway.
inline float nearShare(float coc) {
  return saturate((-coc - kZoneOfFocusCoc) / kZoneOfFocusCoc);
}

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
