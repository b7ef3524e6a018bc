// The deferred image of a Lambertian plane under one light against analytic radiance.
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <map>
#include <string>

#include "core/color.h"
#include "scene/builtin_scenes.h"
#include "scene/primitives.h"
#include "shading/blinn_phong.h"
#include "shading/gbuffer_sample.h"
#include "shading/shade_batch.h"
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

// A small deterministic generator of uniforms in [0, 1) for the batch tests.
struct Lcg {
  uint32_t state;
  float operator()() {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / 16777216.0f;
  }
};

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

// Tiled deferred's light culling is exact: a batch shaded with only the lights cullLights keeps
// equals the batch shaded with all of them, bit for bit, and the spot and the ranged light are
// left out of batches they cannot reach.
TEST(ShadeBatch, CulledLightsContributeNothing) {
  ShadingContext ctx;
  Light spot, ranged, sun;
  spot.type = LightType::Spot;
  spot.position = {0, 5, 0};
  spot.direction = {0, -1, 0};
  spot.innerConeDeg = 10;
  spot.outerConeDeg = 20;
  ranged.position = {6, 1, 0};
  ranged.range = 2;
  sun.type = LightType::Directional;
  sun.direction = normalize(Vec3(0.3f, -1, 0.2f));
  for (const Light& l : {spot, ranged, sun}) ctx.lights.push_back(PreparedLight::from(l));
  Lcg uniform{7};
  int spotCulled = 0, rangedCulled = 0;
  for (int batch = 0; batch < 200; ++batch) {
    ShadeBatch all, culled;
    const Vec3 base{uniform() * 16 - 8, 0, uniform() * 16 - 8};
    for (int k = 0; k < ShadeBatch::kMax; ++k) {
      SurfaceSample s;
      s.position = base + Vec3(uniform(), 0, uniform()) * 0.5f;
      s.normal = {0, 1, 0};
      s.diffuse = {0.5f, 0.4f, 0.3f};
      s.specular = {0.2f, 0.2f, 0.2f};
      s.specularExponent = 32;
      all.set(k, s, normalize(Vec3(0.1f, 1, 0.3f)));
    }
    all.count = ShadeBatch::kMax;
    culled = all;
    std::vector<uint32_t> list;
    cullLights(culled, ctx, list);
    spotCulled += std::find(list.begin(), list.end(), 0u) == list.end();
    rangedCulled += std::find(list.begin(), list.end(), 1u) == list.end();
    EXPECT_NE(std::find(list.begin(), list.end(), 2u), list.end());  // the sun always
    shadeBatch(all, ctx);
    shadeBatch(culled, ctx);
    for (int k = 0; k < ShadeBatch::kMax; ++k)
      for (int c = ShadeBatch::OR; c <= ShadeBatch::OB; ++c)
        ASSERT_EQ(all.f[c][k], culled.f[c][k]) << "batch " << batch << " lane " << k;
  }
  EXPECT_GT(spotCulled, 100);  // the cone covers a disc of radius ~1.8 m out of 16 x 16 m
  EXPECT_GT(rangedCulled, 100);
}

// One shading function: a 16-lane batch (deferred shading) and batches of one (ray hits through
// shadeBlinnPhong) give the same radiance for the same surfaces, with and without visibility.
TEST(ShadeBatch, WideBatchesMatchSingleHits) {
  Scene scene = makeAtriumScene();
  const ShadingContext ctx = ShadingContext::from(scene);
  Lcg uniform{11};
  ShadeBatch wide;
  SurfaceSample samples[ShadeBatch::kMax];
  Vec3 wos[ShadeBatch::kMax];
  std::vector<float> vis(3 * ctx.lights.size() * ShadeBatch::kMax);
  std::vector<Vec3> visOne(ctx.lights.size() * ShadeBatch::kMax);
  for (int k = 0; k < ShadeBatch::kMax; ++k) {
    SurfaceSample& s = samples[k];
    s.position = {uniform() * 20 - 10, uniform() * 4, uniform() * 10 - 5};
    s.normal = normalize(Vec3(uniform() - 0.5f, 1.0f, uniform() - 0.5f));
    s.diffuse = {uniform(), uniform(), uniform()};
    s.specular = k % 3 ? Vec3(uniform(), uniform(), uniform()) : Vec3(0.0f);
    s.specularExponent = 1 + 200 * uniform();
    s.emission = {0.01f * uniform(), 0, 0};
    s.ambient = s.diffuse;
    wos[k] = normalize(Vec3(uniform() - 0.5f, 1.0f, uniform() - 0.5f));
    wide.set(k, s, wos[k]);
    for (size_t i = 0; i < ctx.lights.size(); ++i) {
      const Vec3 v = k % 2 ? Vec3(uniform(), uniform(), uniform()) : Vec3(1.0f);
      visOne[size_t(k) * ctx.lights.size() + i] = v;
      for (int c = 0; c < 3; ++c) vis[(3 * i + size_t(c)) * ShadeBatch::kMax + size_t(k)] = v[c];
    }
  }
  wide.count = ShadeBatch::kMax;
  ShadeBatch wideVis = wide;
  shadeBatch(wide, ctx);
  shadeBatch(wideVis, ctx, vis.data());
  for (int k = 0; k < ShadeBatch::kMax; ++k) {
    const Vec3 one = shadeBlinnPhong(samples[k], wos[k], ctx);
    const Vec3 oneVis =
        shadeBlinnPhong(samples[k], wos[k], ctx, &visOne[size_t(k) * ctx.lights.size()]);
    EXPECT_GT(maxComponent(one), 0.0f);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(wide.result(k)[c], one[c], 1e-5f * (1 + std::abs(one[c]))) << k;
      EXPECT_NEAR(wideVis.result(k)[c], oneVis[c], 1e-5f * (1 + std::abs(oneVis[c]))) << k;
    }
  }
}

// The kernels are compiled for several instruction sets and dispatched at run time: every target
// this machine can run (AVX-512, AVX2, SSE4, the baseline) shades and tonemaps alike, so a machine
// with another vector width renders the same images. Targets without FMA round multiply-adds
// twice, and the specular pow amplifies that by its exponent (up to 118 here): 2e-4 relative,
// far below what an image shows (80 dB).
TEST(ShadeBatch, EveryInstructionSetAgrees) {
  Scene scene = makeAtriumScene();
  const ShadingContext ctx = ShadingContext::from(scene);
  ShadeBatch batch;
  for (int k = 0; k < 11; ++k) {  // a partial batch: the tail lanes are masked
    SurfaceSample s;
    s.position = {float(k) - 5.0f, 0.5f * float(k % 3), 1.0f - 0.3f * float(k)};
    s.normal = normalize(Vec3(0.1f * float(k), 1.0f, -0.2f));
    s.diffuse = {0.6f, 0.5f, 0.4f};
    s.specular = {0.3f, 0.3f, 0.3f};
    s.specularExponent = 8.0f + 10.0f * float(k);
    batch.set(k, s, normalize(Vec3(0.3f, 1.0f, 0.5f)));
  }
  batch.count = 11;
  std::vector<float> hdr;
  for (int i = 0; i < 33; ++i) hdr.push_back(0.05f * float(i));
  const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  std::vector<ShadeBatch> shaded;
  std::vector<std::vector<float>> mapped;
  for (int64_t target : targets) {
    hwy::SetSupportedTargetsForTest(target);
    ShadeBatch b = batch;
    shadeBatch(b, ctx);
    shaded.push_back(b);
    std::vector<float> out(hdr.size());
    tonemapSpan(hdr.data(), out.data(), hdr.size(), 0.0f, ToneOperator::Aces);
    mapped.push_back(out);
    // An unaligned span with a partial last vector (a tile's row in the middle of an image):
    // the same values, and nothing written past its end (the next tile's pixels).
    std::vector<float> shifted(hdr.size() + 2, -7.0f);
    tonemapSpan(hdr.data() + 1, shifted.data() + 1, hdr.size() - 2, 0.0f, ToneOperator::Aces);
    for (size_t i = 1; i + 1 < hdr.size(); ++i)
      EXPECT_EQ(shifted[i], out[i]) << hwy::TargetName(target) << " value " << i;
    EXPECT_EQ(shifted[hdr.size() - 1], -7.0f) << hwy::TargetName(target);
  }
  hwy::SetSupportedTargetsForTest(0);  // back to what the machine supports
  for (size_t t = 1; t < targets.size(); ++t) {
    for (int k = 0; k < batch.count; ++k)
      for (int c = ShadeBatch::OR; c <= ShadeBatch::OB; ++c)
        EXPECT_NEAR(shaded[t].f[c][k], shaded[0].f[c][k], 2e-4f * (1 + shaded[0].f[c][k]))
            << hwy::TargetName(targets[t]) << " lane " << k;
    for (size_t i = 0; i < hdr.size(); ++i)
      EXPECT_NEAR(mapped[t][i], mapped[0][i], 1e-5f) << hwy::TargetName(targets[t]);
  }
  std::printf("targets compared:");
  for (int64_t t : targets) std::printf(" %s", hwy::TargetName(t));
  std::printf("\n");
}

// Deferred shading loads whole runs of foreground pixels in vectors (GBufferReader::readSpan):
// every lane, eye direction included, bit-identical to reading the pixels one by one, on every
// instruction set; a run that touches the background is refused.
TEST(GBufferReader, SpansMatchPixelByPixelOnEveryInstructionSet) {
  constexpr int kW = 3 * ShadeBatch::kMax, kH = 2;
  std::map<std::string, Buffer> bufs;
  uint32_t state = 12345;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24);
  };
  for (const BufferSlot& slot : gbufferSampleSlots()) {
    Buffer b(kW, kH, slot.channels);
    for (float& v : b.data) v = 4.0f * next() - 2.0f;
    bufs[slot.slot] = b;
  }
  Buffer& ids = bufs["object_id"];
  for (size_t i = 0; i < ids.data.size(); ++i) ids.data[i] = float(i % 3);
  ids.at(2 * ShadeBatch::kMax + 5, 1)[0] = -1.0f;  // the last run of row 1 sees the sky
  Buffer& pos = bufs["position"];
  pos.setRgb(3, 0, Vec3(0.5f, 1.0f, 2.0f));  // exactly at the eye: a zero eye direction
  const GBufferReader g([&](const BufferSlot& s) -> const Buffer& { return bufs[s.slot]; });
  const Vec3 eye(0.5f, 1.0f, 2.0f), minusForward = normalize(Vec3(0.2f, -0.1f, -1.0f));
  const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  for (int64_t target : targets) {
    hwy::SetSupportedTargetsForTest(target);
    for (bool perspective : {true, false})
      for (int y = 0; y < kH; ++y)
        for (int x0 = 0; x0 < kW; x0 += ShadeBatch::kMax) {
          SCOPED_TRACE(std::string(hwy::TargetName(target)) + " x0 " + std::to_string(x0) + " y " +
                       std::to_string(y) + (perspective ? " perspective" : " ortho"));
          ShadeBatch span, lanes;
          Bounds3 box, expected;
          const bool whole = g.readSpan(x0, y, ShadeBatch::kMax, span, perspective,
                                        perspective ? eye : minusForward, box);
          EXPECT_EQ(whole, !(y == 1 && x0 == 2 * ShadeBatch::kMax));
          if (!whole) continue;
          for (int k = 0; k < ShadeBatch::kMax; ++k) {
            ASSERT_TRUE(g.read(x0 + k, y, lanes, k));
            const Vec3 p{lanes.f[ShadeBatch::PX][k], lanes.f[ShadeBatch::PY][k],
                         lanes.f[ShadeBatch::PZ][k]};
            const Vec3 wo = perspective ? normalize(eye - p) : minusForward;
            lanes.f[ShadeBatch::WX][k] = wo.x, lanes.f[ShadeBatch::WY][k] = wo.y;
            lanes.f[ShadeBatch::WZ][k] = wo.z;
            expected.extend(p);
          }
          EXPECT_EQ(box.lo.x, expected.lo.x);
          EXPECT_EQ(box.lo.y, expected.lo.y);
          EXPECT_EQ(box.lo.z, expected.lo.z);
          EXPECT_EQ(box.hi.x, expected.hi.x);
          EXPECT_EQ(box.hi.y, expected.hi.y);
          EXPECT_EQ(box.hi.z, expected.hi.z);
          for (int f = 0; f < ShadeBatch::OR; ++f)
            for (int k = 0; k < ShadeBatch::kMax; ++k)
              ASSERT_EQ(span.f[f][k], lanes.f[f][k]) << "field " << f << " lane " << k;
        }
  }
  hwy::SetSupportedTargetsForTest(0);
}
