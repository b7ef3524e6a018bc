// LDR-FLIP: zero for identical images, the analytic value for flat colours (no features, so
// FLIP is the remapped HyAB colour distance), symmetry, monotonicity in noise, and locality.
#include <gtest/gtest.h>

#include <cmath>

#include "eval/metrics/flip.h"
#include "rt/sampler.h"

using namespace tandem;

namespace {
Buffer flat(int w, int h, Vec3 c) {
  Buffer b(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) b.setRgb(x, y, c);
  return b;
}

// The colour term for two flat colours from their Hunt-adjusted L*a*b* (computed by hand from the
// CIE L*a*b* of sRGB black, white, green (87.737, -86.185, 83.181) and blue (32.303, 79.197,
// -107.864), D65).
double flatFlip(double hyabDistance) {
  auto hunt = [](double L, double a, double b, double out[3]) {
    out[0] = L, out[1] = 0.01 * L * a, out[2] = 0.01 * L * b;
  };
  double g[3], b[3];
  hunt(87.737, -86.185, 83.181, g);
  hunt(32.303, 79.197, -107.864, b);
  const double cmax = std::pow(std::abs(g[0] - b[0]) + std::hypot(g[1] - b[1], g[2] - b[2]), 0.7);
  const double d = std::pow(hyabDistance, 0.7);
  return d < 0.4 * cmax ? 0.95 / (0.4 * cmax) * d : 0.95 + (d - 0.4 * cmax) / (0.6 * cmax) * 0.05;
}
}  // namespace

TEST(Flip, IdenticalImagesAreZero) {
  Buffer a(48, 32, 3);
  for (size_t i = 0; i < a.data.size(); ++i) a.data[i] = float(i % 97) / 96.0f;
  Buffer map;
  EXPECT_EQ(flip(a, a, &map), 0.0);
  for (float v : map.data) EXPECT_EQ(v, 0.0f);
}

TEST(Flip, FlatColoursGiveTheRemappedHyabDistance) {
  // Black against white: HyAB = 100 (L* only).
  const double bw = flip(flat(40, 30, {0, 0, 0}), flat(40, 30, {1, 1, 1}));
  EXPECT_NEAR(bw, flatFlip(100.0), 1e-3);
  EXPECT_GT(bw, 0.95);
  // Mid grey (sRGB 0.5, L* = 53.389) against black: below the knee of the remap.
  const double gb = flip(flat(40, 30, {0, 0, 0}), flat(40, 30, {0.5f, 0.5f, 0.5f}));
  EXPECT_NEAR(gb, flatFlip(53.389), 2e-3);
}

TEST(Flip, SymmetricAndGrowsWithNoise) {
  Buffer ref(64, 48, 3);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) ref.setRgb(x, y, {x / 64.0f, y / 48.0f, 0.3f});
  auto noisy = [&](float amount) {
    Buffer b = ref;
    for (size_t i = 0; i < b.data.size(); ++i) {
      const float u = SobolSampler(1, i, 0).uniform() - 0.5f;
      b.data[i] = std::clamp(b.data[i] + amount * u, 0.0f, 1.0f);
    }
    return b;
  };
  const Buffer n1 = noisy(0.05f), n2 = noisy(0.2f), n3 = noisy(0.6f);
  EXPECT_NEAR(flip(ref, n2), flip(n2, ref), 1e-6);
  const double f1 = flip(ref, n1), f2 = flip(ref, n2), f3 = flip(ref, n3);
  EXPECT_GT(f1, 0.0);
  EXPECT_LT(f1, f2);
  EXPECT_LT(f2, f3);
}

// A vertical edge moved by two pixels: the error sits at the edge and vanishes far from it.
TEST(Flip, ErrorIsLocalToTheDifference) {
  Buffer a(96, 16, 3), b(96, 16, 3);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 96; ++x) {
      a.setRgb(x, y, Vec3(x < 48 ? 0.2f : 0.8f));
      b.setRgb(x, y, Vec3(x < 50 ? 0.2f : 0.8f));
    }
  Buffer map;
  flip(a, b, &map);
  EXPECT_GT(map.at(49, 8)[0], 0.3f);
  EXPECT_LT(map.at(5, 8)[0], 1e-3f);
  EXPECT_LT(map.at(90, 8)[0], 1e-3f);
}
