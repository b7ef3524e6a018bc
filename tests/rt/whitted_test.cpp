// Ray-traced effects against geometry and the paper's rules; hybrid vs ray-tracing-only.
#include <gtest/gtest.h>

#include "eval/metrics/metrics.h"
#include "rt/whitted.h"
#include "scene/builtin_scenes.h"
#include "scene/loaders.h"
#include "scene/primitives.h"
#include "shading/surface_resolve.h"
#include "test_util.h"

using namespace tandem;

namespace {

CameraDesc frontCamera(Vec3 pos, Vec3 at, float vfov = 40) {
  CameraDesc c;
  c.position = pos;
  c.lookAt = at;
  c.vfovDeg = vfov;
  return c;
}

// A shadow ray straight up from `origin` to y = 5 (through the test sheets at y = 1).
Ray upRay(Vec3 origin) {
  Ray r;
  r.origin = origin;
  r.dir = {0, 1, 0};
  r.tfar = 5;
  return r;
}

Material diffuse(Vec3 c) {
  Material m;
  m.diffuse = c;
  m.ambient = c;
  return m;
}

}  // namespace

TEST(Whitted, CombineEffectsFollowsEquations5And6) {
  Vec3 M(1, 0, 0), R(0, 1, 0), C(0, 0, 1);
  // Opaque, not reflective: just the lighting. Mirror: the reflection. Clear glass: refraction.
  EXPECT_NEAR(combineEffects(0, 0, M, R, C).z, 1.0f, 1e-6f);
  EXPECT_NEAR(combineEffects(1, 0, M, R, C).x, 1.0f, 1e-6f);
  EXPECT_NEAR(combineEffects(0, 1, M, R, C).y, 1.0f, 1e-6f);
  // OM = 0.5, OR = 0.5: C_M = (.5, .25, .25), C_R = (.25, .5, .25) -> average.
  Vec3 v = combineEffects(0.5f, 0.5f, M, R, C);
  EXPECT_NEAR(v.x, 0.375f, 1e-6f);
  EXPECT_NEAR(v.y, 0.375f, 1e-6f);
  EXPECT_NEAR(v.z, 0.25f, 1e-6f);
}

TEST(Whitted, SnellAndTotalInternalReflection) {
  Vec3 n(0, 1, 0), out;
  Vec3 d = normalize(Vec3(1, -1, 0));  // 45 degrees incidence
  ASSERT_TRUE(refractDir(d, n, 1.0f / 1.5f, out));
  float sinT = out.x;
  EXPECT_NEAR(sinT, std::sin(radians(45)) / 1.5f, 1e-5f);
  // From glass to air at 45 degrees: beyond the critical angle asin(1/1.5) = 41.8 degrees.
  EXPECT_FALSE(refractDir(d, n, 1.5f, out));
  Vec3 r = reflectDir(d, n);
  EXPECT_NEAR(r.y, -d.y, 1e-6f);
}

// A glass sphere of IOR 1.0 and opacity 0 leaves the background unchanged.
TEST(Whitted, NeutralGlassIsInvisible) {
  Scene s;
  int plane = s.addMesh(makePlane(1));
  Texture checker = checkerTexture(64, 8, {0.9f, 0.1f, 0.1f}, {0.1f, 0.1f, 0.9f});
  Material wall = diffuse({1, 1, 1});
  wall.diffuseTexture = s.addTexture(checker);
  s.addObject("wall", plane, s.addMaterial(wall), Transform{{0, 0, -3}, {90, 0, 0}, {4, 1, 4}});
  Light l;
  l.type = LightType::Directional;
  l.direction = {0, 0, -1};
  l.intensity = 3;
  s.lights.push_back(l);
  Scene withSphere = s;
  Material glass = diffuse({0, 0, 0});
  glass.ior = 1.0f;
  glass.opacity = 0.0f;
  glass.castsShadows = false;
  withSphere.addObject("glass", withSphere.addMesh(makeUvSphere(48, 24)),
                       withSphere.addMaterial(glass), Transform{{0, 0, 0}, {}, {1, 1, 1}});
  CameraDesc cam = frontCamera({0, 0, 5}, {0, 0, 0});
  auto a = test::renderOnce(s, "rt-only", 96, 96, cam);
  auto b = test::renderOnce(withSphere, "rt-only", 96, 96, cam);
  const Buffer &ha = a->context().input("hdr"), &hb = b->context().input("hdr");
  // Tolerance: max 2% relative per pixel (ray offsets at the two sphere surfaces shift the
  // wall hit by ~1e-4 m; a checker edge may flip one pixel), RMSE < 1e-3.
  EXPECT_LT(rmse(ha, hb), 2e-2);
  size_t bad = 0;
  for (size_t i = 0; i < ha.data.size(); ++i)
    if (std::abs(ha.data[i] - hb.data[i]) > 0.02f * std::max(ha.data[i], 0.05f)) ++bad;
  EXPECT_LE(bad, ha.data.size() / 200);
}

// IOR 1.5 turns the background upside down through the sphere (a ball lens).
TEST(Whitted, DenseGlassInvertsBackground) {
  Scene s;
  int plane = s.addMesh(makePlane(1));
  Material top = diffuse({1, 0, 0}), bottom = diffuse({0, 0, 1});
  top.emission = {1, 0, 0};
  bottom.emission = {0, 0, 1};
  s.addObject("top", plane, s.addMaterial(top), Transform{{0, 2, -6}, {90, 0, 0}, {8, 1, 2}});
  s.addObject("bottom", plane, s.addMaterial(bottom),
              Transform{{0, -2, -6}, {90, 0, 0}, {8, 1, 2}});
  Material glass = diffuse({0, 0, 0});
  glass.ior = 1.5f;
  glass.opacity = 0.0f;
  s.addObject("lens", s.addMesh(makeUvSphere(64, 32)), s.addMaterial(glass), Transform{});
  auto r = test::renderOnce(s, "rt-only", 64, 64, frontCamera({0, 0, 8}, {0, 0, 0}, 20));
  const Buffer& hdr = r->context().input("hdr");
  // Looking through the upper half of the lens we see the bottom (blue) wall, and vice versa.
  Vec3 upper = hdr.rgb(32, 24), lower = hdr.rgb(32, 40);
  EXPECT_GT(upper.z, upper.x) << "upper half should show the lower, blue wall";
  EXPECT_GT(lower.x, lower.z) << "lower half should show the upper, red wall";
}

// A mirror floor reflects a sphere where the law of reflection puts it: the mirror image of an
// emissive sphere at height h appears at the camera ray that hits the floor point between them.
TEST(Whitted, MirrorReflectsSphereWhereGeometrySays) {
  Scene s;
  Material mirror = diffuse({0, 0, 0});
  mirror.reflectivity = 1.0f;
  s.addObject("floor", s.addMesh(makePlane(1)), s.addMaterial(mirror),
              Transform{{0, 0, 0}, {}, {20, 1, 20}});
  Material glow = diffuse({0, 0, 0});
  glow.emission = {0, 5, 0};
  s.addObject("ball", s.addMesh(makeUvSphere(32, 16)), s.addMaterial(glow),
              Transform{{0, 1, -4}, {}, {0.3f, 0.3f, 0.3f}});
  s.skybox.color = {0, 0, 0};
  CameraDesc cam = frontCamera({0, 1, 4}, {0, 0.5f, -4}, 40);
  auto r = test::renderOnce(s, "rt-only", 128, 128, cam);
  Camera c = Camera::make(cam, 128, 128);
  // Mirror image of the ball centre: (0, -1, -4); seen where the ray to it crosses y = 0.
  Vec2 px;
  ASSERT_TRUE(c.project({0, -1, -4}, px));
  const Buffer& hdr = r->context().input("hdr");
  EXPECT_GT(hdr.rgb(int(px.x), int(px.y)).y, 1.0f)
      << "reflection missing at " << px.x << "," << px.y;
  // And the direct image is where the ball itself projects.
  ASSERT_TRUE(c.project({0, 1, -4}, px));
  EXPECT_GT(hdr.rgb(int(px.x), int(px.y)).y, 1.0f);
}

// Listing 8b: a shadow ray through an occluder of opacity o and diffuse d keeps (1-o)(1-d).
TEST(Whitted, PartialTransparencyAttenuatesShadow) {
  Scene s;
  Material occluder = diffuse({0.2f, 0.5f, 0.8f});
  occluder.opacity = 0.4f;
  occluder.doubleSided = true;
  s.addObject("sheet", s.addMesh(makePlane(1)), s.addMaterial(occluder),
              Transform{{0, 1, 0}, {}, {1, 1, 1}});
  FrameScene fs;
  fs.update(s, 0, 0);
  RayTracer rt;
  rt.update(fs);
  const Ray r = upRay({0, 0, 0});
  Vec3 t = rt.transmittance(r);
  EXPECT_NEAR(t.x, 0.6f * 0.8f, 1e-6f);
  EXPECT_NEAR(t.y, 0.6f * 0.5f, 1e-6f);
  EXPECT_NEAR(t.z, 0.6f * 0.2f, 1e-6f);
  // Two sheets multiply; an opaque one blocks; one that casts no shadow is ignored.
  Scene two = s;
  two.addObject("sheet2", two.meshes.size() - 1, two.objects[0].material,
                Transform{{0, 2, 0}, {}, {1, 1, 1}});
  fs.update(two, 0, 0);
  rt.update(fs);
  EXPECT_NEAR(rt.transmittance(r).x, 0.48f * 0.48f, 1e-6f);
  Material noShadow = diffuse({1, 1, 1});
  noShadow.castsShadows = false;
  two.materials[two.objects[1].material] = occluder;
  two.objects[1].material = two.addMaterial(noShadow);
  fs.update(two, 0, 0);
  rt.update(fs);
  EXPECT_NEAR(rt.transmittance(r).x, 0.48f, 1e-6f);
}

// Shadow packets: each lane of transmittance8 attenuates on its own and equals the single-ray
// query, whatever mix of one sheet, two sheets, an opaque block and a miss the lanes see;
// inactive lanes are left untouched.
TEST(Whitted, ShadowPacketLanesEqualSingleRays) {
  Scene s;
  Material glass = diffuse({0.2f, 0.5f, 0.8f});
  glass.opacity = 0.4f;
  glass.doubleSided = true;
  const size_t plane = s.addMesh(makePlane(1));
  const int mat = s.addMaterial(glass);
  s.addObject("low", plane, mat, Transform{{0, 1, 0}, {}, {1, 1, 1}});
  s.addObject("high", plane, mat, Transform{{1, 2, 0}, {}, {1, 1, 1}});
  s.addObject("wall", s.addMesh(makeCube()), s.addMaterial(diffuse({1, 1, 1})),
              Transform{{-2, 1.5f, 0}, {}, {0.5f, 0.5f, 0.5f}});
  FrameScene fs;
  fs.update(s, 0, 0);
  RayTracer rt;
  rt.update(fs);
  // x = -2: the cube; -0.5: the low sheet; 0.9: both; 1.3: the high sheet only; 4: nothing.
  const float xs[8] = {-2.0f, -0.5f, 0.9f, 1.3f, 4.0f, 0.2f, -1.9f, 1.1f};
  Ray rays[8];
  bool active[8];
  Vec3 out[8];
  for (int k = 0; k < 8; ++k) {
    rays[k] = upRay({xs[k], 0, 0.1f * float(k - 4)});
    active[k] = k != 5;
    out[k] = Vec3(-7.0f);
  }
  rt.transmittance8(rays, active, out);
  for (int k = 0; k < 8; ++k) {
    if (!active[k]) {
      EXPECT_EQ(out[k].x, -7.0f) << "inactive lane " << k << " written";
      continue;
    }
    const Vec3 single = rt.transmittance(rays[k]);
    EXPECT_NEAR(out[k].x, single.x, 1e-6f) << "lane " << k;
    EXPECT_NEAR(out[k].y, single.y, 1e-6f) << "lane " << k;
    EXPECT_NEAR(out[k].z, single.z, 1e-6f) << "lane " << k;
  }
  // The cases differ, so the comparison above is not between equal numbers by accident.
  EXPECT_EQ(out[0].x, 0.0f);
  EXPECT_NEAR(out[1].x, 0.48f, 1e-6f);
  EXPECT_NEAR(out[2].x, 0.48f * 0.48f, 1e-6f);
  EXPECT_NEAR(out[3].x, 0.48f, 1e-6f);
  EXPECT_EQ(out[4].x, 1.0f);
}

// The area of a cube's shadow on the floor under a point light matches the geometry: a unit
// square occluder at height h under a light at height H casts a square of side H / (H - h).
TEST(Whitted, ShadowAreaUnderPointLight) {
  Scene s;
  s.addObject("floor", s.addMesh(makePlane(1)), s.addMaterial(diffuse({0.8f, 0.8f, 0.8f})),
              Transform{{0, 0, 0}, {}, {10, 1, 10}});
  Material card = diffuse({0.5f, 0.5f, 0.5f});
  card.doubleSided = true;
  s.addObject("card", s.addMesh(makePlane(1)), s.addMaterial(card),
              Transform{{0, 1, 0}, {}, {0.5f, 1, 0.5f}});
  Light l;
  l.type = LightType::Point;
  l.position = {0, 3, 0};
  l.intensity = 30;
  s.lights.push_back(l);
  // Orthographic top view, 8 x 8 m, 200 x 200 pixels: each pixel is 0.04 x 0.04 m.
  CameraDesc cam;
  cam.projection = Projection::Orthographic;
  cam.position = {0, 10, 0};
  cam.lookAt = {0, 0, 0};
  cam.up = {0, 0, -1};
  cam.orthoHeight = 8;
  cam.nearPlane = 0.1f;
  cam.farPlane = 50;
  auto r = test::renderOnce(s, "hybrid-all", 200, 200, cam);
  const Buffer& shadow = r->context().input("shadow");
  const Buffer& ids = r->context().input("object_id");
  // Floor pixels in shadow (shadow buffer clearly below 1); the card itself hides the centre.
  size_t shadowed = 0, cardPixels = 0;
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 200; ++x) {
      if (ids.at(x, y)[0] == 1) ++cardPixels;
      if (ids.at(x, y)[0] == 0 && shadow.at(x, y)[0] < 0.999f) ++shadowed;
    }
  double side = 1.0 * 3.0 / (3.0 - 1.0);                  // 1.5 m
  double expected = (side * side - 1.0) / (0.04 * 0.04);  // shadow area not covered by the card
  EXPECT_NEAR(double(cardPixels), 1.0 / (0.04 * 0.04), 0.05 * 625);
  EXPECT_NEAR(double(shadowed), expected, 0.05 * expected);
}

// hybrid-all and rt-only ray trace the same objects: their images agree. Tolerance: SSIM >= 0.99
// and PSNR >= 35 dB on the tonemapped output (edge pixels where primary visibility differs by a
// sample, and float differences between eq. 4's L - (1 - S) and direct shadowed shading).
class HybridVsRayTracing : public ::testing::TestWithParam<std::string> {};

TEST_P(HybridVsRayTracing, AgreeByMetric) {
  Scene s = loadScene(GetParam());
  auto a = test::renderOnce(s, "hybrid-all", 240, 135, s.camera);
  auto b = test::renderOnce(s, "rt-only", 240, 135, s.camera);
  ImageMetrics m = compareImages(a->output(), b->output());
  EXPECT_GE(m.ssim, 0.99);
  EXPECT_GE(m.psnr, 35.0);
}

INSTANTIATE_TEST_SUITE_P(Builtins, HybridVsRayTracing,
                         ::testing::Values("cornell", "spheres", "atrium"));

TEST(Whitted, Deterministic) {
  Scene s = loadScene("spheres");
  auto a = test::renderOnce(s, "hybrid-heuristic", 160, 90, s.camera);
  auto b = test::renderOnce(s, "hybrid-heuristic", 160, 90, s.camera);
  EXPECT_EQ(a->output().data, b->output().data);
}

// Listing 8b with a textured occluder: the diffuse colour the shadow ray attenuates by is the
// textured one (as the G-buffer holds it); `textured = false` uses the base colour.
TEST(Whitted, ShadowAttenuationUsesTheTexturedDiffuse) {
  Scene s;
  Material occluder = diffuse({1, 1, 1});
  occluder.opacity = 0.5f;
  occluder.doubleSided = true;
  // A uniform texture (0.25, 0.5, 0.75): the textured diffuse is base x texel.
  occluder.diffuseTexture =
      s.addTexture(checkerTexture(8, 4, {0.25f, 0.5f, 0.75f}, {0.25f, 0.5f, 0.75f}));
  s.addObject("sheet", s.addMesh(makePlane(1)), s.addMaterial(occluder),
              Transform{{0, 1, 0}, {}, {1, 1, 1}});
  FrameScene fs;
  fs.update(s, 0, 0);
  RayTracer rt;
  rt.update(fs);
  const Ray r = upRay({0.1f, 0, 0.2f});
  // Texel values go through the texture's decoding: compare with what resolveSurface gives.
  Vec3 o = r.origin, d = r.dir;
  const SurfaceSample sh = resolveSurface(fs, 0, 0, o, d);
  const SurfaceSample sh1 = resolveSurface(fs, 0, 1, o, d);
  const Vec3 kd = sh.diffuse.x > 0 ? sh.diffuse : sh1.diffuse;
  ASSERT_LT(kd.x, 0.9f);  // the texture darkened it
  const Vec3 t = rt.transmittance(r);
  EXPECT_NEAR(t.x, 0.5f * (1.0f - kd.x), 1e-3f);
  EXPECT_NEAR(t.z, 0.5f * (1.0f - kd.z), 1e-3f);
  const Vec3 base = rt.transmittance(r, /*textured=*/false);
  EXPECT_NEAR(base.x, 0.0f, 1e-6f);  // base diffuse 1: nothing passes
}

// Listing 8c at the maximum depth: a pure mirror seen by the last allowed ray contributes no
// lighting (0); shade_at_max_depth shades it with Blinn-Phong instead. And Listing 8a: outside the
// heuristic mask all three buffers are 0.
TEST(Whitted, PaperRulesAtMaxDepthAndOutsideTheMask) {
  Scene s;
  Material mirror = diffuse({0.8f, 0.8f, 0.8f});
  mirror.reflectivity = 1.0f;
  mirror.doubleSided = true;
  const int plane = s.addMesh(makePlane(1));
  // Two mirrors facing each other; the camera looks at one through the gap.
  s.addObject("a", plane, s.addMaterial(mirror), Transform{{0, 0, -2}, {90, 0, 0}, {3, 1, 3}});
  s.addObject("b", plane, s.addMaterial(mirror), Transform{{0, 0, 2}, {90, 0, 0}, {3, 1, 3}});
  Light l;
  l.type = LightType::Directional;
  l.direction = normalize(Vec3(0.2f, -1, -0.3f));
  l.intensity = 2;
  s.lights.push_back(l);
  s.ambient = {0.1f, 0.1f, 0.1f};
  const CameraDesc cam = frontCamera({0, 0, 1}, {0, 0, -2}, 30);
  auto render = [&](std::vector<std::string> sets) {
    Pipeline p = Pipeline::load("hybrid-all");
    for (auto& a : sets) p.setParam(a, "test");
    Renderer r(s, std::move(p), RenderSettings{.width = 16, .height = 16});
    r.renderFrame(0, cam);
    return r.context().input("reflection");
  };
  const Buffer paper = render({"rt_secondary.max_depth=1"});
  const Buffer shaded =
      render({"rt_secondary.max_depth=1", "rt_secondary.shade_at_max_depth=true"});
  // Depth 1 hits mirror b: in the paper's rule its colour is 0 (no bounce left, no lighting).
  EXPECT_EQ(paper.rgb(8, 8).x, 0.0f);
  EXPECT_GT(shaded.rgb(8, 8).x, 0.01f);

  // Nothing selected: every buffer 0 (Listing 8a), or a neutral shadow on request.
  Pipeline p = Pipeline::load("hybrid-heuristic");
  p.setParam("heuristic.budget=0", "test");
  p.setParam("deferred_shading.shadows=off", "test");
  p.setParam("heuristic.shadows=budget", "test");  // the paper's rule: nothing at all traced
  Renderer none(s, std::move(p), RenderSettings{.width = 16, .height = 16});
  none.renderFrame(0, cam);
  for (const char* b : {"shadow", "reflection", "refraction"})
    for (float v : none.context().input(b).data) ASSERT_EQ(v, 0.0f) << b;
  none.pipeline().setParam("rt_secondary.outside_mask_shadow=1", "test");
  none.renderFrame(1, cam);
  for (float v : none.context().input("shadow").data) ASSERT_EQ(v, 1.0f);
}

// A clear pane with a transmission filter (OBJ Tf) in front of a white sky: what passes through
// is the sky times the filter, in the Whitted ray tracer and in the path tracer alike.
TEST(TransmissionFilter, TintsWhatPassesThroughInWhittedAndPathTracer) {
  Scene s;
  Material glass;
  glass.diffuse = glass.specular = Vec3(0.0f);
  glass.opacity = 0.0f;
  glass.ior = 1.0f;  // no bending: the pixel sees the sky straight behind
  glass.transmissionFilter = {0.5f, 1.0f, 0.25f};
  glass.doubleSided = true;
  Transform xf;
  xf.rotationDeg = {90, 0, 0};  // facing the camera (+z)
  xf.scale = {3, 1, 3};
  s.addObject("pane", s.addMesh(makePlane()), s.addMaterial(glass), xf);
  s.skybox.color = {1, 1, 1};
  CameraDesc cam;
  cam.position = {0, 0, 3};
  cam.lookAt = {0, 0, 0};
  for (const char* pipeline : {"rt-only", "reference"}) {
    const Buffer img = test::renderHdr(s, pipeline, cam, {}, 0.0f, 32, 32);
    const Vec3 c = img.rgb(16, 16);
    // The pane is one surface, crossed once: sky * filter.
    EXPECT_NEAR(c.x, 0.5f, 0.02f) << pipeline;
    EXPECT_NEAR(c.y, 1.0f, 0.02f) << pipeline;
    EXPECT_NEAR(c.z, 0.25f, 0.02f) << pipeline;
  }
}
