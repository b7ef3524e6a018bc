// The progressive reference renderer: convergence rate, motion blur, polygonal aperture, the
// process split used by MPI, time limits, the variance estimate and energy conservation.
#include <gtest/gtest.h>

#include <cmath>

#include "eval/metrics/metrics.h"
#include "passes/baselines/pt_reference.h"
#include "rt/reference_render.h"
#include "scene/loaders.h"
#include "scene/primitives.h"
#include "test_util.h"

using namespace tandem;

namespace {

std::unique_ptr<Renderer> reference(const Scene& s, const CameraDesc& cam, int w, int h, int spp,
                                    uint64_t seed = 0, float shutter = 0.0f,
                                    const CameraDesc* close = nullptr,
                                    SampleCluster* cluster = nullptr) {
  Pipeline p = Pipeline::load("reference");
  p.setParam("pt_reference.spp=" + std::to_string(spp), "test");
  auto r = std::make_unique<Renderer>(
      s, std::move(p), RenderSettings{.width = w, .height = h, .seed = seed, .shutter = shutter});
  for (auto& pass : r->pipeline().passes)
    if (auto* pt = dynamic_cast<PTReferencePass*>(pass.get())) pt->distribute(cluster);
  r->renderFrameAt(0, 0.0f, cam, close ? *close : cam);
  return r;
}

class FakeRank : public SampleCluster {
 public:
  FakeRank(int rank, int ranks) {
    rank_ = rank;
    ranks_ = ranks;
  }
};

// An unlit emissive square (half-width 0.1, radiance 1) seen from above by an orthographic
// camera 2 x 1 world units wide, 64 x 32 pixels (1/32 per pixel).
Scene emissiveSquare(Material* out = nullptr) {
  Scene s;
  Material m;
  m.diffuse = {0, 0, 0};
  m.specular = {0, 0, 0};
  m.emission = {1, 1, 1};
  m.doubleSided = true;
  if (out) *out = m;
  Transform xf;
  xf.scale = {0.1f, 1, 0.1f};
  s.addObject("square", s.addMesh(makePlane()), s.addMaterial(m), xf);
  s.skybox.color = {0, 0, 0};
  return s;
}

CameraDesc topDown(float x = 0) {
  CameraDesc c;
  c.projection = Projection::Orthographic;
  c.position = {x, 5, 0};
  c.lookAt = {x, 0, 0};
  c.up = {0, 0, -1};
  c.orthoHeight = 1.0f;
  return c;
}

double sum(const Buffer& b, int c = 1) {
  double s = 0;
  for (size_t i = 0; i < b.pixelCount(); ++i) s += b.data[i * size_t(b.channels) + size_t(c)];
  return s;
}

}  // namespace

// The error of an unbiased estimator falls like 1/sqrt(spp): two renders with independent seeds
// differ by sqrt(2) sigma, so their RMSE must fall by at least half per 4x samples (scrambled
// Sobol points do better on the smooth parts of the integrand: 0.39 and 0.21 here). The Cornell box
// is made diffuse: caustic paths through its glass have heavy-tailed noise whose RMSE, measured
// once on a small image, swings too much to show the rate.
TEST(ReferenceRender, ErrorFallsLikeOneOverSqrtSpp) {
  Scene s = loadScene("cornell");
  for (Material& m : s.materials) m.reflectivity = 0, m.opacity = 1, m.specular = Vec3(0.0f);
  std::vector<double> err;
  for (int spp : {4, 16, 64}) {
    auto a = reference(s, s.camera, 48, 27, spp, 1), b = reference(s, s.camera, 48, 27, spp, 2);
    err.push_back(rmse(a->context().input("hdr"), b->context().input("hdr")));
  }
  ASSERT_GT(err[0], 0.0);
  for (int i = 0; i + 1 < 3; ++i) {
    const double ratio = err[size_t(i) + 1] / err[size_t(i)];
    EXPECT_LT(ratio, 0.6) << i;   // 1/sqrt(4) = 0.5, with room for the noise of the estimate
    EXPECT_GT(ratio, 0.05) << i;  // no faster than any sampler can go on a discontinuous image
  }
}

// A square moving 1 unit along x while the shutter is open paints exactly its swept path: inside
// the path every point is covered 0.2 of the time, outside nothing, and the image holds the
// square's energy (radiance x area) whatever the motion.
TEST(ReferenceRender, MotionBlurCoversExactlyTheSweptPath) {
  Scene s = emissiveSquare();
  Transform a, b;
  a.position = {-0.5f, 0, 0};
  b.position = {0.5f, 0, 0};
  s.objects[0].animation = {{0.0f, a}, {1.0f, b}};
  auto r = reference(s, topDown(), 64, 32, 256, 0, 1.0f);
  const Buffer& hdr = r->context().input("hdr");
  const float px = 1.0f / 32.0f;
  double interior = 0;
  int interiorCount = 0;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      const float wx = -1.0f + (float(x) + 0.5f) * px, wz = -0.5f + (float(y) + 0.5f) * px;
      const float v = hdr.at(x, y)[1];
      if (std::abs(wx) - px / 2 > 0.6f || std::abs(wz) - px / 2 > 0.1f) {
        EXPECT_EQ(v, 0.0f) << x << "," << y;  // never under the square
      } else if (std::abs(wx) + px / 2 < 0.4f && std::abs(wz) + px / 2 < 0.1f) {
        // Covered 0.2 of the shutter. Pixel position and time are separately stratified, not
        // jointly, so one pixel's estimate has a spread of about 0.015 at 256 samples.
        EXPECT_NEAR(v, 0.2f, 0.04f) << x << "," << y;
        interior += v;
        ++interiorCount;
      }
    }
  ASSERT_GT(interiorCount, 100);
  EXPECT_NEAR(interior / interiorCount, 0.2, 0.003);
  EXPECT_NEAR(sum(hdr) * px * px, 0.04, 0.04 * 0.01);  // 1 x area 0.2^2, 1 %
  EXPECT_FALSE(r->context().frame.objects[0].stepPositions.empty());

  // The same relative motion from the camera: a static square, the camera sweeping the other way.
  Scene still = emissiveSquare();
  CameraDesc open = topDown(0.5f), close = topDown(-0.5f);
  auto c = reference(still, open, 64, 32, 256, 0, 1.0f, &close);
  EXPECT_LT(rmse(c->context().input("hdr"), hdr), 0.01);
  // Without a shutter nothing blurs: the square at its frame position only.
  auto sharp = reference(s, topDown(), 64, 32, 16);
  EXPECT_EQ(sharp->context().input("hdr").at(32, 16)[1], 0.0f);  // the square is at x = -0.5
  EXPECT_NEAR(sharp->context().input("hdr").at(16, 16)[1], 1.0f, 1e-6f);
}

// A regular n-gon aperture: lens points uniform over the polygon (none outside, each of the n
// fan triangles gets 1/n, the inscribed disk gets its area share), still focused on the plane.
TEST(ReferenceRender, PolygonalApertureIsUniformOverThePolygon) {
  CameraDesc cd;
  cd.position = {0, 0, 0};
  cd.lookAt = {0, 0, -1};
  cd.apertureDiameter = 0.2f;
  cd.focusDistance = 4.0f;
  cd.apertureBlades = 6;
  cd.apertureRotationDeg = 10;
  Camera cam = Camera::make(cd, 64, 64);
  const int n = 6, count = 1 << 14;
  const float R = 0.1f, inR = R * std::cos(kPi / n);
  Vec3 o0, d0;
  cam.generateRay(20.5f, 30.5f, o0, d0);
  const Vec3 focus = o0 + d0 * (4.0f / -d0.z);
  std::vector<int> sector(n, 0);
  int inDisk = 0;
  for (int i = 0; i < count; ++i) {
    const Vec2 u = SobolSampler(7, 0, uint32_t(i)).get2D();
    Vec3 o, d;
    cam.generateThinLensRay(20.5f, 30.5f, u.x, u.y, o, d);
    const float ang = std::atan2(o.y, o.x) - radians(10.0f);
    const float a = std::fmod(ang + 4 * kPi, 2 * kPi / n) - kPi / n;   // angle from edge normal
    ASSERT_LE(std::hypot(o.x, o.y) * std::cos(a), inR * (1 + 1e-4f));  // inside every edge
    sector[size_t(std::fmod(ang + 4 * kPi, 2 * kPi) / (2 * kPi / n)) % n]++;
    inDisk += std::hypot(o.x, o.y) < inR;
    ASSERT_LT(length(o + d * ((-4.0f - o.z) / d.z) - focus), 1e-4f);
  }
  for (int k = 0; k < n; ++k) EXPECT_NEAR(sector[size_t(k)], count / n, count / n * 0.02) << k;
  const double hexArea = 0.5 * n * R * R * std::sin(2 * kPi / n);
  EXPECT_NEAR(double(inDisk) / count, kPi * inR * inR / hexArea, 0.01);
}

// What MPI does, in one process: each rank renders its rows; the sum of the parts is exactly the
// single-process image.
TEST(ReferenceRender, RowSplitSumsToTheSingleProcessImage) {
  Scene s = loadScene("cornell");
  auto whole = reference(s, s.camera, 40, 30, 8, 3);
  FakeRank r0(0, 2), r1(1, 2);
  auto a = reference(s, s.camera, 40, 30, 8, 3, 0, nullptr, &r0);
  auto b = reference(s, s.camera, 40, 30, 8, 3, 0, nullptr, &r1);
  const Buffer &w = whole->context().input("hdr"), &pa = a->context().input("hdr"),
               &pb = b->context().input("hdr");
  int fromA = 0;
  for (size_t i = 0; i < w.data.size(); ++i) {
    ASSERT_EQ(w.data[i], pa.data[i] + pb.data[i]) << i;
    ASSERT_TRUE(pa.data[i] == 0.0f || pb.data[i] == 0.0f) << i;  // one owner per pixel
    fromA += pa.data[i] != 0.0f;
  }
  EXPECT_GT(fromA, int(w.data.size()) / 4);
  EXPECT_LT(fromA, int(w.data.size()) * 3 / 4);
}

// A time limit stops at a whole batch: fewer samples than asked, at least one, a finite image;
// the variance estimate falls like 1/spp.
TEST(ReferenceRender, TimeLimitAndVarianceEstimate) {
  Scene s = loadScene("cornell");
  Pipeline p = Pipeline::load("reference");
  p.setParam("pt_reference.spp=1000000", "test");
  p.setParam("pt_reference.time_limit=0.2", "test");
  Renderer r(s, std::move(p), RenderSettings{.width = 64, .height = 36});
  r.renderFrame(0, s.camera);
  EXPECT_GE(int(r.context().counters.at("spp")), 1);
  EXPECT_LT(int(r.context().counters.at("spp")), 1000000);
  for (float v : r.context().input("hdr").data) ASSERT_TRUE(std::isfinite(v));

  auto lo = reference(s, s.camera, 48, 27, 16), hi = reference(s, s.camera, 48, 27, 64);
  const double vLo = sum(lo->context().input("variance"), 0),
               vHi = sum(hi->context().input("variance"), 0);
  ASSERT_GT(vLo, 0.0);
  EXPECT_NEAR(vHi / vLo, 0.25, 0.08);
}

// Energy is never created: under a uniform sky of radiance 1, no material reflects more than 1
// on average (glossy Blinn-Phong lobes of any exponent, a diffuse + glossy mix, coloured albedo).
TEST(ReferenceRender, NoMaterialCreatesEnergy) {
  std::vector<Material> mats(4);
  mats[0].diffuse = {0, 0, 0}, mats[0].specular = {1, 1, 1}, mats[0].specularExponent = 10;
  mats[1].diffuse = {0, 0, 0}, mats[1].specular = {1, 1, 1}, mats[1].specularExponent = 500;
  mats[2].diffuse = {0.7f, 0.7f, 0.7f}, mats[2].specular = {0.6f, 0.6f, 0.6f};
  mats[3].diffuse = {0.9f, 0.2f, 0.1f}, mats[3].specular = {0, 0, 0};
  for (const Material& m : mats) {
    Scene s;
    s.addObject("sphere", s.addMesh(makeUvSphere(64, 32)), s.addMaterial(m));
    s.skybox.color = {1, 1, 1};
    CameraDesc cam;
    cam.position = {0, 0, 2.2f};
    cam.lookAt = {0, 0, 0};
    cam.vfovDeg = 40;
    auto r = reference(s, cam, 32, 32, 64);
    const Buffer& hdr = r->context().input("hdr");
    for (int c = 0; c < 3; ++c) EXPECT_LE(sum(hdr, c) / double(hdr.pixelCount()), 1.005) << c;
  }
}
