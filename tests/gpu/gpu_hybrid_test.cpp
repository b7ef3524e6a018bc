// Walewski et al. 2019's hybrid with its passes on the GPU against the CPU: rt_secondary's
// shadow, reflection and refraction buffers and traced mask, and the composited image, of
// `hybrid-all` (every reflective and transparent object and every shadow ray traced) on the
// built-in scenes and the feature scene, over three frames of a moving camera.
#include <gtest/gtest.h>

#include "gpu/feature_scene.h"
#include "gpu/gpu_test_util.h"
#include "pipeline/renderer.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {
namespace {

void compareHybrid(const std::shared_ptr<GpuDevice>& dev, const std::string& pipeline,
                   const Scene& scene, CameraDesc cam, const std::string& what) {
  RenderSettings rs{.width = 160, .height = 90};
  // Every shadow traced: rt_secondary's GPU version (classified shadows need the shadow maps).
  const auto load = [&] {
    Pipeline p = Pipeline::load(pipeline);
    p.setParam("rt_secondary.shadows=rays", "test");
    return p;
  };
  Renderer cpu(scene, load(), rs);
  rs.gpu = dev;
  Renderer gpu(scene, load(), rs);
  const Vec3 step = (cam.lookAt - cam.position) * 0.02f + Vec3(0.05f, 0.0f, 0.0f);
  for (int f = 0; f < 3; ++f) {
    cpu.renderFrame(f, cam);
    const FrameTimings ft = gpu.renderFrame(f, cam);
    bool onGpu = false;  // a GPU pass has a row of its host time
    for (const PassTiming& t : ft.passes) onGpu |= t.name == "rt_secondary/host";
    EXPECT_TRUE(onGpu);
    const std::string at = pipeline + ", " + what + ", frame " + std::to_string(f);
    const FrameContext &c = cpu.context(), &g = gpu.context();
    const Buffer &cIds = c.input("object_id"), &gIds = g.input("object_id");
    for (const char* name : {"shadow", "reflection", "refraction", "traced_mask", "composite"})
      expectAgreement(imageAgreement(c.input(name), g.input(name), cIds, gIds), at + ": " + name);
    expectAgreement(imageAgreement(cpu.output(), gpu.output(), cIds, gIds), at + ": output");
    // The same work: rays within 1 % (near-ties of which light a pixel asks about).
    const double cpuRays = c.counter("rt_secondary/shadow_traced", -1),
                 gpuRays = g.counter("rt_secondary/shadow_traced", -2);
    EXPECT_NEAR(gpuRays, cpuRays, 0.01 * cpuRays + 1) << at;
    cam.position = cam.position + step;
  }
}

TEST(GpuHybrid, SecondaryEffectsMatchTheCpu) {
  REQUIRE_GPU(dev);
  for (const char* name : {"cornell", "spheres", "atrium"}) {
    const Scene scene = loadScene(name);
    compareHybrid(dev, "hybrid-all", scene, defaultCamera(scene), name);
  }
  compareHybrid(dev, "hybrid-all", featureScene(), featureCamera(), "features");
  expectNoValidationMessages(*dev);
}

// The heuristic's selection with ss_fallback standing in for what it leaves out: blend reads the
// fallback buffer on the GPU.
TEST(GpuHybrid, HeuristicHybridMatchesTheCpu) {
  REQUIRE_GPU(dev);
  const Scene spheres = loadScene("spheres");
  compareHybrid(dev, "hybrid-heuristic", spheres, defaultCamera(spheres), "spheres");
  compareHybrid(dev, "hybrid-heuristic", featureScene(), featureCamera(), "features");
  expectNoValidationMessages(*dev);
}

}  // namespace
}  // namespace tandem
