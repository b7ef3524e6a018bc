// Low-discrepancy points used across the framework: the radical inverse (van der Corput), the
// Halton (2, 3) projection jitter of TAA and accumulation, Hammersley points.
#pragma once
#include <cstdint>

#include "core/math.h"

namespace tandem {

inline float radicalInverse(uint32_t i, uint32_t base) {
  float f = 1.0f, r = 0.0f;
  while (i > 0) {
    f /= float(base);
    r += f * float(i % base);
    i /= base;
  }
  return r;
}

// The i-th point (i >= 1) of the Halton (2, 3) sequence, minus 0.5: a jitter in pixels.
inline Vec2 haltonJitter(int i) {
  return {radicalInverse(uint32_t(i), 2) - 0.5f, radicalInverse(uint32_t(i), 3) - 0.5f};
}

// Hammersley point i of n in [0,1)^2.
inline Vec2 hammersley(int i, int n) {
  return {(float(i) + 0.5f) / float(n), radicalInverse(uint32_t(i), 2)};
}

}  // namespace tandem
