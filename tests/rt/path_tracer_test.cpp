// The reference path tracer against analytic answers.
#include <gtest/gtest.h>

#include <cmath>

#include "rt/path_tracer.h"
#include "scene/loaders.h"
#include "scene/primitives.h"
#include "test_util.h"

using namespace tandem;

namespace {

std::unique_ptr<Renderer> renderReference(const Scene& s, const CameraDesc& cam, int w, int h,
                                          int spp, int maxDepth) {
  Pipeline p = Pipeline::load("reference");
  p.setParam("pt_reference.spp=" + std::to_string(spp), "test");
  p.setParam("pt_reference.max_depth=" + std::to_string(maxDepth), "test");
  auto r = std::make_unique<Renderer>(s, std::move(p), RenderSettings{.width = w, .height = h});
  r->renderFrame(0, cam);
  return r;
}

double meanChannel(const Buffer& b, int c) {
  double sum = 0;
  for (size_t i = 0; i < b.pixelCount(); ++i) sum += b.data[i * size_t(b.channels) + size_t(c)];
  return sum / double(b.pixelCount());
}

}  // namespace

// White furnace: inside a closed diffuse box of albedo rho whose walls all emit Le, radiance is
// Le / (1 - rho) everywhere (the geometric series of bounces).
TEST(PathTracer, WhiteFurnace) {
  Scene s;
  Material m;
  m.diffuse = {0.5f, 0.5f, 0.5f};
  m.specular = {0, 0, 0};
  m.emission = {1, 1, 1};
  m.doubleSided = true;
  s.addObject("box", s.addMesh(makeCube()), s.addMaterial(m));
  s.skybox.color = {0, 0, 0};
  CameraDesc cam;
  cam.position = {0, 0, 0.5f};
  cam.lookAt = {0, 0, -1};
  auto r = renderReference(s, cam, 32, 32, 64, 200);
  const Buffer& hdr = r->context().input("hdr");
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(meanChannel(hdr, c), 2.0, 0.04) << c;  // 2 %
}

// A Lambertian plane under a point light: L = rho / pi * I cos(theta) / d^2, one bounce only
// (nothing else to hit), so the only noise is the pixel jitter.
TEST(PathTracer, LambertPlaneUnderPointLight) {
  Scene s;
  Material m;
  m.diffuse = {0.8f, 0.8f, 0.8f};
  m.specular = {0, 0, 0};
  Transform big;
  big.scale = {100, 1, 100};
  s.addObject("plane", s.addMesh(makePlane()), s.addMaterial(m), big);
  Light l;
  l.type = LightType::Point;
  l.position = {0, 2, 0};
  l.intensity = 10;
  s.lights.push_back(l);
  s.skybox.color = {0, 0, 0};
  CameraDesc cam;
  cam.position = {0, 3, 0.001f};
  cam.lookAt = {0, 0, 0};
  cam.vfovDeg = 40;
  auto r = renderReference(s, cam, 33, 33, 16, 4);
  const Buffer& hdr = r->context().input("hdr");
  const double expectCentre = 0.8 / kPi * 10 / (2.0 * 2.0);
  EXPECT_NEAR(hdr.at(16, 16)[1], expectCentre, 0.01 * expectCentre);
  // Off-centre pixels: the point they see, and the analytic radiance there.
  for (int x : {2, 8, 24, 30}) {
    Vec3 o, d;
    r->context().camera().generateRay(x + 0.5f, 16.5f, o, d);
    Vec3 p = o + d * (-o.y / d.y);
    Vec3 toL = l.position - p;
    double dist = length(toL), cosT = toL.y / dist;
    double expect = 0.8 / kPi * 10 * cosT / (dist * dist);
    EXPECT_NEAR(hdr.at(x, 16)[1], expect, 0.03 * expect) << x;  // jitter across the pixel
  }
}

// Same seed, same image; the image does not depend on the thread count.
TEST(PathTracer, Deterministic) {
  Scene s = loadScene("cornell");
  auto a = renderReference(s, s.camera, 40, 24, 4, 8);
  auto b = renderReference(s, s.camera, 40, 24, 4, 8);
  EXPECT_EQ(a->output().data, b->output().data);
  for (float v : a->context().input("hdr").data) ASSERT_TRUE(std::isfinite(v));
}

// Classic white furnace: under a uniform sky of radiance 1, a lossless object (white Lambert,
// perfect mirror, clear glass) is invisible — every pixel is 1. Energy is neither lost nor made.
TEST(PathTracer, LosslessMaterialsVanishInAUniformSky) {
  Material white, mirror, glass;
  white.diffuse = {1, 1, 1};
  white.specular = {0, 0, 0};
  mirror.reflectivity = 1;
  glass.opacity = 0;
  glass.ior = 1.5f;
  for (const Material& m : {white, mirror, glass}) {
    Scene s;
    s.addObject("sphere", s.addMesh(makeUvSphere(64, 32)), s.addMaterial(m));
    s.skybox.color = {1, 1, 1};
    CameraDesc cam;
    cam.position = {0, 0, 4};
    cam.lookAt = {0, 0, 0};
    auto r = renderReference(s, cam, 24, 24, 64, 64);
    const Buffer& hdr = r->context().input("hdr");
    EXPECT_NEAR(meanChannel(hdr, 0), 1.0, 0.01);
    for (float v : hdr.data) EXPECT_LT(v, 1.3f);  // single pixels: noise, never a bright bias
  }
}

// Thin lens: every lens sample of a pixel passes through one point of the focus plane (sharp),
// and at depth z the rays spread over a disk of diameter A |z - z_f| / z_f (the circle of
// confusion in world units at that depth).
TEST(PathTracer, ThinLensFocusAndCircleOfConfusion) {
  CameraDesc cd;
  cd.position = {0, 0, 0};
  cd.lookAt = {0, 0, -1};
  cd.apertureDiameter = 0.2f;
  cd.focusDistance = 4.0f;
  Camera cam = Camera::make(cd, 64, 64);
  const float zFar = 10.0f;
  float minX = 1e9f, maxX = -1e9f, minY = 1e9f, maxY = -1e9f, focusSpread = 0.0f;
  Vec3 o0, d0;
  cam.generateRay(40.5f, 20.5f, o0, d0);
  const Vec3 focusPoint = o0 + d0 * (4.0f / -d0.z);
  for (int i = 0; i < 4000; ++i) {
    Vec3 o, d;
    const Vec2 u = SobolSampler(1, 2, uint32_t(i)).get2D();
    cam.generateThinLensRay(40.5f, 20.5f, u.x, u.y, o, d);
    ASSERT_NEAR(o.z, 0.0f, 1e-6f);
    ASSERT_LE(std::hypot(o.x, o.y), 0.1f + 1e-5f);  // on the aperture disk
    Vec3 atFocus = o + d * ((-4.0f - o.z) / d.z);
    focusSpread = std::max(focusSpread, length(atFocus - focusPoint));
    Vec3 atFar = o + d * ((-zFar - o.z) / d.z);
    minX = std::min(minX, atFar.x), maxX = std::max(maxX, atFar.x);
    minY = std::min(minY, atFar.y), maxY = std::max(maxY, atFar.y);
  }
  EXPECT_LT(focusSpread, 1e-4f);
  const float coc = 0.2f * (zFar - 4.0f) / 4.0f;  // 0.3
  EXPECT_NEAR(maxX - minX, coc, 0.01f * coc);
  EXPECT_NEAR(maxY - minY, coc, 0.01f * coc);
  // A zero aperture is the pinhole camera.
  cd.apertureDiameter = 0;
  Camera pin = Camera::make(cd, 64, 64);
  Vec3 o, d;
  pin.generateThinLensRay(40.5f, 20.5f, 0.9f, 0.1f, o, d);
  EXPECT_EQ(length(o - o0), 0.0f);
  EXPECT_NEAR(length(d - d0), 0.0f, 1e-7f);
}
