// rt_whitted on the GPU against the CPU pass: the built-in scenes and a scene made to exercise
// every material feature the GPU's surface resolve ports (texture wraps and mip levels, UV
// transforms, alpha masks and blending, normal maps, metallic-roughness, emission, occlusion and
// specular textures, transmission filters, spot/point/directional lights with ranges, a cube-map
// sky). The images must agree at PSNR >= 45 dB (the bar of every deterministic GPU pass), the
// object ids pixel for pixel but for silhouette grazes, and the rays and shadow queries counted
// on both sides within 1 %.
#include <gtest/gtest.h>

#include <cmath>

#include "eval/metrics/metrics.h"
#include "gpu/gpu_test_util.h"
#include "pipeline/renderer.h"
#include "scene/loaders.h"
#include "scene/primitives.h"
#include "scene/scene_camera.h"

namespace tandem {
namespace {

// A texture of w x h texels from f(x, y) -> RGBA (linear).
template <class F>
Texture makeTexture(int w, int h, bool srgb, F&& f) {
  Texture t;
  t.name = "test";
  t.texels = Buffer(w, h, 4, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Vec4 c = f(x, y);
      float* p = t.texels.at(x, y);
      p[0] = c.x, p[1] = c.y, p[2] = c.z, p[3] = c.w;
    }
  t.srgb = srgb;
  t.buildLevels();
  return t;
}

Scene featureScene() {
  Scene s;
  s.name = "features";
  s.ambient = {0.05f, 0.05f, 0.06f};
  const int plane = s.addMesh(makePlane(2));
  const int sphere = s.addMesh(makeUvSphere(32, 16));
  const int cube = s.addMesh(makeCube());
  // Non-power-of-two sizes (the wrap's division path) and power-of-two ones.
  Texture checker = checkerTexture(96, 6, {0.9f, 0.8f, 0.6f}, {0.2f, 0.25f, 0.3f});
  checker.wrapS = WrapMode::MirroredRepeat;
  checker.wrapT = WrapMode::ClampToEdge;
  const int checkerTex = s.addTexture(checker);
  const int holes = s.addTexture(makeTexture(64, 64, true, [](int x, int y) {
    const bool hole = ((x / 8) + (y / 8)) % 3 == 0;
    return Vec4(0.3f + 0.01f * float(x), 0.6f, 0.2f + 0.01f * float(y), hole ? 0.0f : 1.0f);
  }));
  const int bumps = s.addTexture(makeTexture(64, 32, false, [](int x, int y) {
    const float a = std::sin(float(x) * 0.5f) * 0.4f, b = std::cos(float(y) * 0.7f) * 0.4f;
    return Vec4(0.5f + 0.5f * a, 0.5f + 0.5f * b, 0.9f, 1.0f);
  }));
  const int metalRough = s.addTexture(makeTexture(32, 32, false, [](int x, int y) {
    return Vec4(1.0f, float(y) / 31.0f, float(x) / 31.0f, 1.0f);
  }));
  const int glow = s.addTexture(makeTexture(
      16, 16, true, [](int x, int) { return Vec4(x % 4 == 0 ? 1.0f : 0.0f, 0.5f, 0.1f, 1.0f); }));

  Material floor;
  floor.name = "floor";
  floor.diffuseTexture = checkerTex;
  floor.tiling = {3, 2};
  floor.offset = {0.1f, -0.2f};
  floor.uvRotation = 0.4f;
  floor.specular = {0.3f, 0.3f, 0.3f};
  floor.specularExponent = 60;
  floor.reflectivity = 0.2f;
  floor.occlusionTexture = metalRough;
  floor.occlusionStrength = 0.7f;
  s.addObject("floor", plane, s.addMaterial(floor), {{0, 0, 0}, {0, 0, 0}, {6, 1, 6}});

  Material masked;
  masked.name = "masked";
  masked.diffuseTexture = holes;
  masked.alphaMode = AlphaMode::Mask;
  masked.doubleSided = true;
  s.addObject("screen", plane, s.addMaterial(masked), {{-1.5f, 1.2f, -1}, {80, 20, 0}, {1, 1, 1}});

  Material bumpy;
  bumpy.name = "bumpy";
  bumpy.baseColor = {0.8f, 0.5f, 0.3f};
  bumpy.metallic = 0.8f;
  bumpy.roughness = 0.6f;
  bumpy.metallicRoughnessTexture = metalRough;
  bumpy.diffuseTexture = checkerTex;
  bumpy.normalTexture = bumps;
  bumpy.normalScale = 0.8f;
  bumpy.emissionTexture = glow;
  bumpy.emission = {0.2f, 0.2f, 0.2f};
  bumpy.specularTexture = glow;
  s.addObject("bumpy", sphere, s.addMaterial(bumpy),
              {{0.8f, 0.8f, -0.5f}, {0, 30, 0}, {0.8f, 0.8f, 0.8f}});

  Material glass;
  glass.name = "tinted glass";
  glass.diffuse = {0.1f, 0.1f, 0.1f};
  glass.opacity = 0.2f;
  glass.reflectivity = 0.1f;
  glass.ior = 1.4f;
  glass.transmissionFilter = {0.9f, 0.6f, 0.4f};
  glass.specular = {0.5f, 0.5f, 0.5f};
  glass.specularExponent = 120;
  s.addObject("glass", sphere, s.addMaterial(glass),
              {{-0.6f, 0.6f, 0.8f}, {0, 0, 0}, {0.6f, 0.6f, 0.6f}});

  Material blended;
  blended.name = "blended";
  blended.diffuseTexture = holes;
  blended.alphaMode = AlphaMode::Blend;
  blended.castsShadows = true;
  s.addObject("box", cube, s.addMaterial(blended),
              {{1.8f, 0.52f, 1.2f}, {0, 40, 0}, {0.4f, 0.5f, 0.4f}});

  Material ghost;  // casts no shadow
  ghost.name = "ghost";
  ghost.diffuse = {0.2f, 0.7f, 0.9f};
  ghost.castsShadows = false;
  s.addObject("ghost", cube, s.addMaterial(ghost), {{0, 2.6f, 0}, {20, 0, 10}, {0.3f, 0.1f, 0.3f}});

  Light sun;
  sun.type = LightType::Directional;
  sun.direction = normalize(Vec3{0.4f, -1.0f, -0.3f});
  sun.intensity = 2.0f;
  s.lights.push_back(sun);
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {-2, 3.5f, 2};
  spot.direction = normalize(Vec3{0.5f, -1.0f, -0.5f});
  spot.innerConeDeg = 15;
  spot.outerConeDeg = 35;
  spot.cosinePower = 1.0f;
  spot.intensity = 30;
  spot.color = {1.0f, 0.8f, 0.6f};
  s.lights.push_back(spot);
  Light bulb;
  bulb.position = {1.5f, 1.5f, 2.0f};
  bulb.intensity = 4;
  bulb.range = 4;
  bulb.attConstant = 0.5f;
  bulb.attLinear = 0.2f;
  s.lights.push_back(bulb);
  Light dark;  // no shadows: lit everywhere it reaches
  dark.position = {0, 0.3f, 2.5f};
  dark.intensity = 0.5f;
  dark.castsShadows = false;
  s.lights.push_back(dark);

  // A cube-map sky of six flat faces, each its own colour.
  for (int f = 0; f < 6; ++f)
    s.skybox.faces[f] = s.addTexture(makeTexture(4, 4, true, [f](int x, int y) {
      return Vec4(0.1f * float(f + 1), 0.05f * float(x + 1), 0.08f * float(y + 1), 1.0f);
    }));
  return s;
}

CameraDesc featureCamera() {
  CameraDesc c;
  c.position = {0.5f, 2.2f, 4.5f};
  c.lookAt = {0, 0.6f, 0};
  c.vfovDeg = 55;
  return c;
}

struct Compared {
  double psnr = 0, idAgreement = 0;
  double cpuRays = 0, gpuRays = 0;
  double cpuTraced = 0, gpuTraced = 0;
};

double counter(const Renderer& r, const std::string& name) {
  const auto it = r.context().counters.find(name);
  return it == r.context().counters.end() ? -1 : it->second;
}
double passRays(const FrameTimings& ft, const std::string& pass) {
  for (const PassTiming& t : ft.passes)
    if (t.name == pass) return t.rays;
  return -1;
}

Compared compareRtOnly(const std::shared_ptr<GpuDevice>& dev, const Scene& scene,
                       const CameraDesc& cam, const std::string& params = "") {
  RenderSettings rs{.width = 160, .height = 90};
  Pipeline pc = Pipeline::load("rt-only"), pg = Pipeline::load("rt-only");
  if (!params.empty()) {
    pc.setParam(params, "test");
    pg.setParam(params, "test");
  }
  Renderer cpu(scene, std::move(pc), rs);
  rs.gpu = dev;
  Renderer gpu(scene, std::move(pg), rs);
  const FrameTimings fc = cpu.renderFrame(0, cam), fg = gpu.renderFrame(0, cam);
  Compared c;
  c.psnr = psnr(cpu.output(), gpu.output(), 1.0);
  const Buffer &ic = cpu.context().input("object_id"), &ig = gpu.context().input("object_id");
  size_t same = 0;
  for (size_t i = 0; i < ic.data.size(); ++i) same += ic.data[i] == ig.data[i];
  c.idAgreement = double(same) / double(ic.data.size());
  c.cpuRays = passRays(fc, "rt_whitted");
  c.gpuRays = passRays(fg, "rt_whitted");
  c.cpuTraced = counter(cpu, "rt_whitted/shadow_rays_per_pixel");
  c.gpuTraced = counter(gpu, "rt_whitted/shadow_rays_per_pixel");
  return c;
}

void expectAgreement(const Compared& c, const std::string& what) {
  EXPECT_GE(c.psnr, 45.0) << what;
  EXPECT_GE(c.idAgreement, 0.999) << what;
  EXPECT_GT(c.cpuRays, 0) << what;
  EXPECT_NEAR(c.gpuRays / c.cpuRays, 1.0, 0.01) << what << ": " << c.gpuRays << " vs " << c.cpuRays;
  EXPECT_GE(c.cpuTraced, 0) << what;
  EXPECT_NEAR(c.gpuTraced, c.cpuTraced, 0.01 * std::max(c.cpuTraced, 1.0)) << what;
}

TEST(GpuWhitted, MatchesTheCpuOnTheBuiltInScenes) {
  REQUIRE_GPU(dev);
  for (const char* name : {"cornell", "spheres", "atrium"}) {
    const Scene scene = loadScene(name);
    expectAgreement(compareRtOnly(dev, scene, defaultCamera(scene)), name);
  }
  expectNoValidationMessages(*dev);
}

TEST(GpuWhitted, MatchesTheCpuOnEveryMaterialFeature) {
  REQUIRE_GPU(dev);
  const Scene scene = featureScene();
  expectAgreement(compareRtOnly(dev, scene, featureCamera()), "features");
  // The settings the kernel takes: base-colour shadows, shading at a shallow maximum depth, no
  // culling by share, and a wide cutoff.
  expectAgreement(compareRtOnly(dev, scene, featureCamera(), "rt_whitted.shadow_attenuation=base"),
                  "base attenuation");
  expectAgreement(compareRtOnly(dev, scene, featureCamera(), "rt_whitted.max_depth=2"),
                  "max depth 2");
  expectAgreement(compareRtOnly(dev, scene, featureCamera(), "rt_whitted.shade_at_max_depth=true"),
                  "shade at max depth");
  expectAgreement(compareRtOnly(dev, scene, featureCamera(), "rt_whitted.shadow_cull=0"),
                  "no culling");
  expectAgreement(compareRtOnly(dev, scene, featureCamera(), "rt_whitted.importance_cutoff=0.3"),
                  "cutoff");
  expectNoValidationMessages(*dev);
}

// Classified and map shadows need shadow maps, which the GPU does not draw yet: the pass stays on
// the CPU there, and says so by its timing rows (no GPU row, no moves).
TEST(GpuWhitted, ClassifiedShadowsStayOnTheCpu) {
  REQUIRE_GPU(dev);
  const Scene scene = loadScene("cornell");
  RenderSettings rs{.width = 64, .height = 36};
  rs.gpu = dev;
  Pipeline p = Pipeline::load("rt-only");
  p.setParam("rt_whitted.shadows=classified", "test");
  Renderer r(scene, std::move(p), rs);
  const FrameTimings ft = r.renderFrame(0, defaultCamera(scene));
  bool hostRow = false, whittedRow = false;
  for (const PassTiming& t : ft.passes) {
    hostRow |= t.name == "rt_whitted/host";
    whittedRow |= t.name == "rt_whitted";
  }
  EXPECT_TRUE(whittedRow);
  EXPECT_FALSE(hostRow);  // GPU passes have a host row beside their GPU time
  expectNoValidationMessages(*dev);
}

}  // namespace
}  // namespace tandem
