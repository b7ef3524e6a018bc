// rt_whitted on the GPU against the CPU pass: the built-in scenes and a scene made to exercise
// every material feature the GPU's surface resolve ports (texture wraps and mip levels, UV
// transforms, alpha masks and blending, normal maps, metallic-roughness, emission, occlusion and
// specular textures, transmission filters, spot/point/directional lights with ranges, a cube-map
// sky). The images must agree as every deterministic GPU pass must (imageAgreement: PSNR >= 45
// dB but for near-ties on edges), and the rays and shadow queries counted on both sides within 1 %.
#include <gtest/gtest.h>

#include <cmath>

#include "eval/metrics/metrics.h"
#include "gpu/feature_scene.h"
#include "gpu/gpu_test_util.h"
#include "pipeline/renderer.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {
namespace {

struct Compared {
  ImageAgreement image;
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
  c.image = imageAgreement(cpu.output(), gpu.output(), cpu.context().input("object_id"),
                           gpu.context().input("object_id"));
  c.cpuRays = passRays(fc, "rt_whitted");
  c.gpuRays = passRays(fg, "rt_whitted");
  c.cpuTraced = counter(cpu, "rt_whitted/shadow_rays_per_pixel");
  c.gpuTraced = counter(gpu, "rt_whitted/shadow_rays_per_pixel");
  return c;
}

void expectAgreement(const Compared& c, const std::string& what) {
  expectAgreement(c.image, what);
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

// Classified and map shadows: the frame's shadow maps (drawn on the CPU, copied to the device)
// decide on the GPU what they decide on the CPU, the rest traced.
TEST(GpuWhitted, ShadowMapShadowsMatchTheCpu) {
  REQUIRE_GPU(dev);
  for (const char* name : {"cornell", "atrium"}) {
    const Scene scene = loadScene(name);
    for (const char* mode : {"classified", "maps"}) {
      const std::string what = std::string(name) + ", shadows " + mode;
      expectAgreement(compareRtOnly(dev, scene, defaultCamera(scene),
                                    std::string("rt_whitted.shadows=") + mode),
                      what);
    }
  }
  expectNoValidationMessages(*dev);
}

}  // namespace
}  // namespace tandem
