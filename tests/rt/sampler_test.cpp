// The Owen-scrambled Sobol sampler: stratification (the (0,m,2)-net property of every dimension
// pair), determinism, decorrelation between pairs and pixels.
#include <gtest/gtest.h>

#include <set>

#include "rt/sampler.h"

using namespace tandem;

// The first 2^m samples of any pair put exactly one point in every elementary interval of area
// 2^-m (boxes 2^a x 2^(m-a)), for every pixel and every pair.
TEST(Sampler, EveryPairIsAZeroTwoNet) {
  const int m = 8, n = 1 << m;
  for (uint64_t pixel : {0ull, 7ull, 123456ull})
    for (int pair = 0; pair < 6; ++pair) {
      std::vector<Vec2> pts;
      for (int i = 0; i < n; ++i) {
        SobolSampler s(42, pixel, uint32_t(i));
        Vec2 p;
        for (int k = 0; k <= pair; ++k) p = s.get2D();
        ASSERT_GE(p.x, 0.0f);
        ASSERT_LT(p.x, 1.0f);
        ASSERT_GE(p.y, 0.0f);
        ASSERT_LT(p.y, 1.0f);
        pts.push_back(p);
      }
      for (int a = 0; a <= m; ++a) {
        const int nx = 1 << a, ny = 1 << (m - a);
        std::set<int> cells;
        for (Vec2 p : pts) cells.insert(int(p.x * nx) * ny + int(p.y * ny));
        EXPECT_EQ(int(cells.size()), n) << "pixel " << pixel << " pair " << pair << " a " << a;
      }
    }
}

TEST(Sampler, DeterministicAndDecorrelated) {
  SobolSampler a(1, 5, 9), b(1, 5, 9), otherPixel(1, 6, 9), otherSeed(2, 5, 9);
  Vec2 pa = a.get2D(), pb = b.get2D();
  EXPECT_EQ(pa.x, pb.x);
  EXPECT_EQ(pa.y, pb.y);
  EXPECT_NE(pa.x, otherPixel.get2D().x);
  EXPECT_NE(pa.x, otherSeed.get2D().x);
  // Successive pairs of one sample differ (padding), and their coordinates are uncorrelated over
  // many samples: the sample correlation of pair 0's x and pair 1's x is near zero.
  double sx = 0, sy = 0, sxy = 0, sxx = 0, syy = 0;
  const int n = 4096;
  for (int i = 0; i < n; ++i) {
    SobolSampler s(3, 11, uint32_t(i));
    const double x = s.get2D().x, y = s.get2D().x;
    sx += x, sy += y, sxy += x * y, sxx += x * x, syy += y * y;
  }
  const double cov = sxy / n - sx / n * sy / n;
  const double r = cov / std::sqrt((sxx / n - sx * sx / n / n) * (syy / n - sy * sy / n / n));
  EXPECT_LT(std::abs(r), 0.05);
}

TEST(Sampler, ReferenceValues) {
  // Unscrambled Sobol: dimension 0 is the van der Corput sequence, dimension 1 the second Sobol
  // dimension in index (not Gray-code) order: x_i = XOR of v_k over the bits k of i, with
  // v = 1/2, 3/4, 5/8, ... (0, 1/2, 3/4, 1/4, 5/8, 1/8, ...).
  const double d0[] = {0, 0.5, 0.25, 0.75, 0.125, 0.625};
  const double d1[] = {0, 0.5, 0.75, 0.25, 0.625, 0.125};
  for (uint32_t i = 0; i < 6; ++i) {
    EXPECT_DOUBLE_EQ(sobolDim0(i) / 4294967296.0, d0[i]) << i;
    EXPECT_DOUBLE_EQ(sobolDim1(i) / 4294967296.0, d1[i]) << i;
  }
}
