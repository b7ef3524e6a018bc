#include <gtest/gtest.h>

#include "core/color.h"
#include "core/math.h"
#include "scene/camera.h"

using namespace tandem;

TEST(Math, InverseTimesMatrixIsIdentity) {
  Mat4 m = Mat4::translate({1, 2, 3}) * Mat4::eulerXYZ({10, 20, 30}) * Mat4::scale({2, 3, 4});
  Mat4 i = m * m.inverse();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(i.m[r][c], r == c ? 1.0f : 0.0f, 1e-5f);
}

TEST(Math, QuaternionMatchesAxisRotation) {
  // 90 degrees about Y: (0, sin 45, 0, cos 45).
  Mat4 q = Mat4::fromQuaternion({0, std::sin(kPi / 4), 0, std::cos(kPi / 4)});
  Mat4 r = Mat4::rotateY(kPi / 2);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(q.m[i][j], r.m[i][j], 1e-6f);
}

TEST(Camera, ProjectInvertsGenerateRay) {
  CameraDesc d;
  d.position = {1, 2, 5};
  d.lookAt = {0, 0, 0};
  Camera c = Camera::make(d, 320, 200, {0.25f, -0.125f});
  Vec3 o, dir;
  c.generateRay(100.5f, 50.5f, o, dir);
  Vec2 px;
  ASSERT_TRUE(c.project(o + dir * 3.0f, px));
  EXPECT_NEAR(px.x, 100.5f, 1e-3f);
  EXPECT_NEAR(px.y, 50.5f, 1e-3f);
}

TEST(Camera, ReversedZDepthIsOneAtNearAndFallsWithDistance) {
  CameraDesc d;
  d.position = {0, 0, 0};
  d.lookAt = {0, 0, -1};
  d.nearPlane = 0.1f;
  Camera c = Camera::make(d, 64, 64);
  EXPECT_NEAR(c.depthOf({0, 0, -0.1f}), 1.0f, 1e-6f);
  EXPECT_NEAR(c.depthOf({0, 0, -10.0f}), 0.01f, 1e-6f);
  EXPECT_GT(c.depthOf({0, 0, -1}), c.depthOf({0, 0, -2}));
}

TEST(Color, VectorTonemapMatchesExactCurves) {
  // Every operator against the scalar formulas (exact pow), over [0, 4] plus bad values.
  std::vector<float> in;
  for (int i = 0; i <= 40000; ++i) in.push_back(i / 10000.0f);
  in.insert(in.end(), {-1.0f, std::nanf(""), INFINITY, -INFINITY});
  std::vector<float> out(in.size());
  for (ToneOperator op : {ToneOperator::Clamp, ToneOperator::Reinhard, ToneOperator::Aces}) {
    tonemapSpan(in.data(), out.data(), in.size(), 0.0f, op);
    float worst = 0;
    for (size_t i = 0; i + 4 < in.size(); ++i) {
      float v = in[i];
      float curve = op == ToneOperator::Clamp ? std::min(v, 1.0f)
                    : op == ToneOperator::Reinhard
                        ? v / (1 + v)
                        : std::clamp((v * (2.51f * v + 0.03f)) / (v * (2.43f * v + 0.59f) + 0.14f),
                                     0.0f, 1.0f);
      worst = std::max(worst, std::abs(out[i] - linearToSrgb(curve)));
    }
    EXPECT_LT(worst, 2e-5f);  // half an 8-bit step is 2e-3
    for (size_t i = in.size() - 4; i < in.size(); ++i) EXPECT_EQ(out[i], 0.0f) << in[i];
    // Bad values in whole vectors too (the span's tail takes another path), and a tail of one.
    std::vector<float> bad(33, 0.5f), badOut(33);
    bad[0] = -1.0f, bad[1] = std::nanf(""), bad[2] = INFINITY, bad[17] = -INFINITY;
    tonemapSpan(bad.data(), badOut.data(), bad.size(), 0.0f, op);
    for (size_t i : {0, 1, 2, 17}) EXPECT_EQ(badOut[i], 0.0f) << i;
    for (size_t i : {3, 16, 32}) EXPECT_EQ(badOut[i], badOut[4]) << i;
  }
  // Exposure: +1 stop doubles the linear value.
  float half = 0.25f, encoded;
  tonemapSpan(&half, &encoded, 1, 1.0f, ToneOperator::Clamp);
  EXPECT_NEAR(encoded, linearToSrgb(0.5f), 2e-5f);
}
