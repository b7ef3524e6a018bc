// The deferred image of a Lambertian plane under one light against analytic radiance.
#include <gtest/gtest.h>

#include "scene/primitives.h"
#include "shading/blinn_phong.h"
#include "test_util.h"

using namespace tandem;

namespace {

Scene litPlane(const Light& light, Vec3 albedo) {
  Scene s;
  Material m;
  m.diffuse = albedo;
  m.ambient = {0, 0, 0};
  int mat = s.addMaterial(m);
  s.addObject("floor", s.addMesh(makePlane(8)), mat, Transform{{0, 0, 0}, {0, 0, 0}, {4, 1, 4}});
  s.lights.push_back(light);
  s.skybox.color = {0, 0, 0};
  return s;
}

CameraDesc topCamera() {
  CameraDesc c;
  c.position = {0, 6, 0.001f};
  c.lookAt = {0, 0, 0};
  c.vfovDeg = 60;
  return c;
}

}  // namespace

TEST(BlinnPhong, LambertPlaneUnderPointLightMatchesInverseSquareCosine) {
  Light l;
  l.type = LightType::Point;
  l.position = {0.3f, 2.0f, -0.2f};
  l.intensity = 10;
  const Vec3 albedo{0.5f, 0.4f, 0.3f};
  Scene s = litPlane(l, albedo);
  auto r = test::renderOnce(s, "deferred", 96, 96, topCamera());
  const Buffer& hdr = r->context().input("hdr");
  const Buffer& pos = r->context().input("position");
  const Buffer& id = r->context().input("object_id");
  int checked = 0;
  for (int y = 4; y < 96; y += 9)
    for (int x = 4; x < 96; x += 9) {
      if (id.at(x, y)[0] < 0) continue;
      Vec3 p = pos.rgb(x, y);
      Vec3 d = l.position - p;
      float dist = length(d);
      float cosTheta = d.y / dist;
      // L = rho / pi * I cos(theta) / d^2
      Vec3 expected = albedo * (kInvPi * l.intensity * cosTheta / (dist * dist));
      Vec3 got = hdr.rgb(x, y);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(got[k], expected[k], 1e-4f * std::max(1.0f, expected[k]));
      ++checked;
    }
  EXPECT_GT(checked, 50);
}

TEST(BlinnPhong, DirectionalLightGivesConstantRadiance) {
  Light l;
  l.type = LightType::Directional;
  l.direction = normalize(Vec3(0, -1, -1));
  l.intensity = 3;
  Scene s = litPlane(l, Vec3(0.6f));
  auto r = test::renderOnce(s, "deferred", 32, 32, topCamera());
  float expected = 0.6f * kInvPi * 3.0f * std::cos(radians(45));
  EXPECT_NEAR(r->context().input("hdr").rgb(16, 16).x, expected, 1e-5f);
}

TEST(BlinnPhong, SpotConeFalloff) {
  Light l;
  l.type = LightType::Spot;
  l.position = {0, 2, 0};
  l.direction = {0, -1, 0};
  l.innerConeDeg = 10;
  l.outerConeDeg = 20;
  l.intensity = 4;
  // Inside the inner cone: full intensity; outside the outer cone: none; between: partial.
  LightSample in = sampleLight(l, {0, 0, 0});
  EXPECT_NEAR(in.radiance.x, 1.0f, 1e-6f);      // 4 / 2^2
  LightSample out = sampleLight(l, {2, 0, 0});  // 45 degrees off axis
  EXPECT_EQ(out.radiance.x, 0.0f);
  LightSample mid = sampleLight(l, {2 * std::tan(radians(15)), 0, 0});
  EXPECT_GT(mid.radiance.x, 0.0f);
  EXPECT_LT(mid.radiance.x, 4.0f / (4.0f / std::pow(std::cos(radians(15)), 2.0f)));
}

TEST(BlinnPhong, EmissionAndAmbientAdd) {
  Scene s;
  s.ambient = {0.1f, 0.2f, 0.3f};
  SurfaceSample ss;
  ss.normal = {0, 1, 0};
  ss.emission = {1, 0, 0};
  ss.ambient = {0.5f, 0.5f, 0.5f};
  Vec3 c = shadeBlinnPhong(ss, {0, 1, 0}, s);
  EXPECT_NEAR(c.x, 1.05f, 1e-6f);
  EXPECT_NEAR(c.y, 0.10f, 1e-6f);
  EXPECT_NEAR(c.z, 0.15f, 1e-6f);
}

TEST(BlinnPhong, SpecularPeakMatchesNormalisedLobe) {
  Scene s;
  Light l;
  l.type = LightType::Directional;
  l.direction = {0, -1, 0};
  l.intensity = 1;
  s.lights.push_back(l);
  SurfaceSample ss;
  ss.normal = {0, 1, 0};
  ss.diffuse = {0, 0, 0};
  ss.ambient = {0, 0, 0};
  ss.specular = {1, 1, 1};
  ss.specularExponent = 32;
  // Mirror configuration: H = N, so f = (n + 8) / (8 pi).
  Vec3 c = shadeBlinnPhong(ss, {0, 1, 0}, s);
  EXPECT_NEAR(c.x, (32.0f + 8.0f) / (8.0f * kPi), 1e-5f);
}
