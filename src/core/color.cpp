#include "core/color.h"

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

}  // namespace tandem
