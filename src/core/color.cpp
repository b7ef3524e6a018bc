#include "core/color.h"

#include <algorithm>

#include <array>

namespace tandem {

namespace {
constexpr int kSrgbIntervals = 4096;
const std::array<float, kSrgbIntervals + 1>& srgbTable() {
  static const std::array<float, kSrgbIntervals + 1> table = [] {
    std::array<float, kSrgbIntervals + 1> t{};
    for (int i = 0; i <= kSrgbIntervals; ++i) t[i] = linearToSrgb(float(i) / kSrgbIntervals);
    return t;
  }();
  return table;
}
}  // namespace

float linearToSrgbFast(float c) {
  if (!(c > 0.0f)) return 0.0f;
  if (c >= 1.0f) return 1.0f;
  // Below the first intervals the curve is linear (c * 12.92), where interpolation is exact.
  const auto& t = srgbTable();
  float x = c * kSrgbIntervals;
  int i = int(x);
  float f = x - float(i);
  return t[i] + (t[i + 1] - t[i]) * f;
}

namespace {
float aces(float x) {
  const float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
  return std::clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0f, 1.0f);
}
}  // namespace

Vec3 tonemapPixel(Vec3 c, float ev, ToneOperator op) {
  c = c * std::exp2(ev);
  for (int k = 0; k < 3; ++k) {
    float v = std::isfinite(c[k]) ? std::max(c[k], 0.0f) : 0.0f;
    switch (op) {
      case ToneOperator::Clamp:
        v = std::min(v, 1.0f);
        break;
      case ToneOperator::Reinhard:
        v = v / (1.0f + v);
        break;
      case ToneOperator::Aces:
        v = aces(v);
        break;
    }
    c[k] = linearToSrgbFast(v);
  }
  return c;
}

}  // namespace tandem
