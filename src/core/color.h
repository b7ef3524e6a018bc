// Colour-space transfer functions (IEC 61966-2-1 sRGB).
#pragma once
#include <cmath>
#include <cstddef>

#include "core/math.h"

namespace tandem {

inline float srgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
inline float linearToSrgb(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

enum class ToneOperator { Clamp = 0, Reinhard = 1, Aces = 2 };
// Exposure (2^EV), tone curve and sRGB encoding of n linear channel values (non-finite or
// negative -> 0), vectorised (tonemap_span.cpp). An RGB image is one span of 3 x pixels.
void tonemapSpan(const float* in, float* out, size_t n, float exposureEV, ToneOperator op);
// The same for one colour.
static_assert(sizeof(Vec3) == 3 * sizeof(float), "Vec3 is read as three floats");
inline Vec3 tonemapPixel(Vec3 hdr, float exposureEV, ToneOperator op) {
  Vec3 out;
  tonemapSpan(&hdr.x, &out.x, 3, exposureEV, op);
  return out;
}

inline Vec3 srgbToLinear(Vec3 c) {
  return {srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z)};
}

}  // namespace tandem
