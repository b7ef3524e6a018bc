#include <gtest/gtest.h>

#include <cmath>

#include "eval/metrics/metrics.h"

using namespace tandem;

// Two constant single-channel images: every window sees zero variance, so
// SSIM = (2 mu_a mu_b + C1) / (mu_a^2 + mu_b^2 + C1) exactly, computed here by hand.
TEST(Metrics, SsimOfConstantImagesMatchesHandComputation) {
  Buffer a(8, 8, 1, 0.2f), b(8, 8, 1, 0.6f);
  double c1 = 0.0001;
  double expected = (2 * 0.2 * 0.6 + c1) / (0.04 + 0.36 + c1);  // = 0.600100 / ...
  EXPECT_NEAR(ssim(a, b), expected, 1e-6);
}

// A 1-D two-level step, windows clipped at borders: hand-evaluate the centre pixel of a
// 3x1 image [0, 1, 0] whose Gaussian weights are (w1, 1, w1) with w1 = exp(-1/4.5).
TEST(Metrics, SsimOfTinyImageMatchesHandComputation) {
  Buffer a(3, 1, 1), b(3, 1, 1);
  a.data = {0, 1, 0};
  b.data = {0, 0.5f, 0};
  double w1 = std::exp(-1.0 / 4.5), w2 = std::exp(-4.0 / 4.5);
  double c1 = 1e-4, c2 = 9e-4;
  auto pixelSsim = [&](double wl, double wc, double wr, double xl, double xc, double xr, double yl,
                       double yc, double yr) {
    double s = wl + wc + wr;
    double mx = (wl * xl + wc * xc + wr * xr) / s, my = (wl * yl + wc * yc + wr * yr) / s;
    double exx = (wl * xl * xl + wc * xc * xc + wr * xr * xr) / s;
    double eyy = (wl * yl * yl + wc * yc * yc + wr * yr * yr) / s;
    double exy = (wl * xl * yl + wc * xc * yc + wr * xr * yr) / s;
    double vx = exx - mx * mx, vy = eyy - my * my, cov = exy - mx * my;
    return ((2 * mx * my + c1) * (2 * cov + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
  };
  // Left pixel sees (centre weight 1, +1: w1, +2: w2); centre sees (w1, 1, w1); right mirrors left.
  double left = pixelSsim(1, w1, w2, 0, 1, 0, 0, 0.5, 0);
  double centre = pixelSsim(w1, 1, w1, 0, 1, 0, 0, 0.5, 0);
  double expected = (2 * left + centre) / 3;
  EXPECT_NEAR(ssim(a, b), expected, 1e-6);
}

TEST(Metrics, IdenticalImagesArePerfect) {
  Buffer a(16, 16, 3);
  for (size_t i = 0; i < a.data.size(); ++i) a.data[i] = float((i * 37) % 101) / 100.0f;
  EXPECT_DOUBLE_EQ(ssim(a, a), 1.0);
  EXPECT_EQ(rmse(a, a), 0.0);
  EXPECT_TRUE(std::isinf(psnr(a, a)));
}

TEST(Metrics, RmseAndPsnrOfKnownOffset) {
  Buffer a(4, 4, 3, 0.5f), b(4, 4, 3, 0.6f);
  EXPECT_NEAR(rmse(a, b), 0.1, 1e-6);
  EXPECT_NEAR(psnr(a, b), 20.0, 1e-4);  // 20 log10(1 / 0.1)
}

TEST(Metrics, SsimDropsWithNoise) {
  Buffer a(32, 32, 1), b(32, 32, 1);
  for (int i = 0; i < 32 * 32; ++i) {
    a.data[i] = float((i % 32) / 31.0);
    b.data[i] = a.data[i] + ((i * 7919) % 13 - 6) * 0.02f;
  }
  double s = ssim(a, b);
  EXPECT_LT(s, 0.95);
  EXPECT_GT(s, 0.0);
}
