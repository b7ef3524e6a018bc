// Shared image filters against values worked out by hand.
#include "core/image_filters.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace tandem;

namespace {
Buffer gray(int w, int h, std::initializer_list<float> v) {
  Buffer b(w, h, 1);
  std::copy(v.begin(), v.end(), b.data.begin());
  return b;
}
}  // namespace

TEST(ImageFilters, GaussianOfAnImpulseIsTheNormalisedKernel) {
  Buffer b(9, 9, 1);
  b.at(4, 4)[0] = 1.0f;
  const Buffer g = gaussianBlur(b, 1.0f);  // radius 3
  // 1-D weights exp(-x^2/2) / sum over x in [-3, 3]; the 2-D value is their product.
  double sum = 0;
  for (int x = -3; x <= 3; ++x) sum += std::exp(-0.5 * x * x);
  const double w0 = 1.0 / sum, w1 = std::exp(-0.5) / sum, w2 = std::exp(-2.0) / sum;
  EXPECT_NEAR(g.at(4, 4)[0], w0 * w0, 1e-6);
  EXPECT_NEAR(g.at(5, 4)[0], w1 * w0, 1e-6);
  EXPECT_NEAR(g.at(5, 5)[0], w1 * w1, 1e-6);
  EXPECT_NEAR(g.at(2, 4)[0], w2 * w0, 1e-6);
  EXPECT_EQ(g.at(0, 4)[0], 0.0f);  // 4 pixels away: outside the radius
  double total = 0;
  for (float v : g.data) total += v;
  EXPECT_NEAR(total, 1.0, 1e-5);  // energy kept away from the borders
  // Clamp-to-edge: a constant image stays constant, borders included.
  Buffer c(5, 4, 3, 0.7f);
  for (float v : gaussianBlur(c, 2.0f).data) EXPECT_NEAR(v, 0.7f, 1e-6f);
}

TEST(ImageFilters, Sobel5x5OfARampAndAStep) {
  // f(x, y) = 2x + 3y: per unit slope the 5x5 Sobel gives sum(smooth) x sum(derive[t] t)
  // = 16 x (−1·−2 + −2·−1 + 2·1 + 1·2) = 16 x 8 = 128; so d/dx = 256 and d/dy = 384.
  Buffer ramp(7, 7, 1);
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 7; ++x) ramp.at(x, y)[0] = 2.0f * float(x) + 3.0f * float(y);
  const Buffer g = sobel5x5(ramp);
  EXPECT_FLOAT_EQ(g.at(3, 3)[0], 256.0f);
  EXPECT_FLOAT_EQ(g.at(3, 3)[1], 384.0f);
  // A vertical step 0 | 1 between x = 2 and 3: at x = 2 the derivative row sees (0 0 0 2 1) * 1
  // = 3, times the column smoothing 16.
  Buffer step(6, 5, 1);
  for (int y = 0; y < 5; ++y)
    for (int x = 3; x < 6; ++x) step.at(x, y)[0] = 1.0f;
  const Buffer s = sobel5x5(step);
  EXPECT_FLOAT_EQ(s.at(2, 2)[0], 48.0f);
  EXPECT_FLOAT_EQ(s.at(3, 2)[0], 48.0f);
  EXPECT_FLOAT_EQ(s.at(1, 2)[0], 16.0f);
  EXPECT_FLOAT_EQ(s.at(2, 2)[1], 0.0f);
}

TEST(ImageFilters, Median3x3RemovesAnOutlierAndKeepsAnEdge) {
  Buffer b = gray(4, 3,
                  {1, 1, 5, 5,   //
                   1, 99, 5, 5,  //
                   1, 1, 5, 5});
  const Buffer m = median3x3(b);
  EXPECT_EQ(m.at(1, 1)[0], 1.0f);  // {1,1,5,1,99,5,1,1,5}: median 1
  EXPECT_EQ(m.at(2, 1)[0], 5.0f);  // {1,5,5,99,5,5,1,5,5}: median 5
  EXPECT_EQ(m.at(0, 0)[0], 1.0f);  // clamped border {1,1,1,1,1,99,1,1,99}
}

TEST(ImageFilters, DownAndUpsampling) {
  Buffer b = gray(3, 2,
                  {1, 2, 3,  //
                   5, 6, 7});
  const Buffer d = downsampleBox(b);
  ASSERT_EQ(d.width, 2);
  ASSERT_EQ(d.height, 1);
  EXPECT_FLOAT_EQ(d.at(0, 0)[0], 3.5f);  // (1 + 2 + 5 + 6) / 4
  EXPECT_FLOAT_EQ(d.at(1, 0)[0], 5.0f);  // the odd column: (3 + 7) / 2
  // Bilinear: 2x1 -> 4x1 samples at x = 0.25, 0.75 (clamped), 1.25, 1.75 in pixel units.
  Buffer two = gray(2, 1, {0, 8});
  const Buffer up = resizeBilinear(two, 4, 1);
  EXPECT_FLOAT_EQ(up.at(0, 0)[0], 0.0f);
  EXPECT_FLOAT_EQ(up.at(1, 0)[0], 2.0f);
  EXPECT_FLOAT_EQ(up.at(2, 0)[0], 6.0f);
  EXPECT_FLOAT_EQ(up.at(3, 0)[0], 8.0f);
  // Depth-aware: where the full-resolution depth matches only one low-resolution neighbour, the
  // result is that neighbour's value (no bleeding across the depth edge).
  Buffer lowDepth = gray(2, 1, {0.9f, 0.1f});
  Buffer highDepth = gray(4, 1, {0.9f, 0.9f, 0.1f, 0.1f});
  const Buffer da = upsampleDepthAware(two, lowDepth, highDepth);
  EXPECT_NEAR(da.at(1, 0)[0], 0.0f, 1e-3f);
  EXPECT_NEAR(da.at(2, 0)[0], 8.0f, 1e-3f);
  // With equal depths it is plain bilinear.
  const Buffer flat = upsampleDepthAware(two, gray(2, 1, {0.5f, 0.5f}), Buffer(4, 1, 1, 0.5f));
  for (int x = 0; x < 4; ++x) EXPECT_NEAR(flat.at(x, 0)[0], up.at(x, 0)[0], 1e-5f);
}

TEST(ImageFilters, MipChainAndSamplers) {
  Buffer b(5, 3, 1);
  for (size_t i = 0; i < b.data.size(); ++i) b.data[i] = float(i);
  const std::vector<Buffer> mips = mipChain(b);
  ASSERT_EQ(mips.size(), 4u);  // 5x3, 3x2, 2x1, 1x1
  EXPECT_EQ(mips[1].width, 3);
  EXPECT_EQ(mips[1].height, 2);
  EXPECT_EQ(mips[3].width, 1);
  EXPECT_EQ(mips[3].height, 1);
  // Level 1 (0,0): (0 + 1 + 5 + 6) / 4 = 3.
  EXPECT_FLOAT_EQ(mips[1].at(0, 0)[0], 3.0f);
  // Samplers reproduce a linear ramp exactly (Catmull-Rom interpolates, bilinear too).
  Buffer ramp(8, 8, 1);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) ramp.at(x, y)[0] = float(x) + 10.0f * float(y);
  float v = 0;
  sampleBilinear(ramp, 3.25f, 4.75f, &v);
  EXPECT_NEAR(v, 2.75f + 10.0f * 4.25f, 1e-5f);
  sampleCatmullRom(ramp, 3.25f, 4.75f, &v);
  EXPECT_NEAR(v, 2.75f + 10.0f * 4.25f, 1e-4f);
  sampleCatmullRom(ramp, 4.5f, 2.5f, &v);  // a pixel centre: the pixel itself
  EXPECT_NEAR(v, 4.0f + 20.0f, 1e-5f);
}

// The inline fixed-channel bilinear sample agrees with sampleBilinear, inside and outside the
// image (clamp to edge).
TEST(ImageFilters, SampleBilinearNAgreesWithSampleBilinear) {
  Buffer b(7, 5, 3);
  for (size_t i = 0; i < b.data.size(); ++i) b.data[i] = float((i * 37) % 11) * 0.1f;
  for (float y = -3.0f; y < 8.0f; y += 0.37f)
    for (float x = -3.0f; x < 10.0f; x += 0.41f) {
      float a[3], c[3];
      sampleBilinear(b, x, y, a);
      sampleBilinearN<3>(b, x, y, c);
      for (int k = 0; k < 3; ++k) ASSERT_NEAR(a[k], c[k], 1e-6f) << x << "," << y;
    }
}
