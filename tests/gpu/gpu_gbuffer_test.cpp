// rt_gbuffer and deferred_shading on the GPU against their CPU passes: every G-buffer target
// (depth and motion included, under a moving camera and a moving object) and the shaded image of
// `deferred-rt-gbuffer`, on the built-in scenes and the feature scene, over three frames.
#include <gtest/gtest.h>

#include <cmath>

#include "eval/metrics/metrics.h"
#include "gpu/feature_scene.h"
#include "gpu/gpu_test_util.h"
#include "pipeline/renderer.h"
#include "raster/gbuffer.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {
namespace {

void compareFrames(const std::shared_ptr<GpuDevice>& dev, const Scene& scene, CameraDesc cam,
                   const std::string& what) {
  RenderSettings rs{.width = 160, .height = 90};
  Renderer cpu(scene, Pipeline::load("deferred-rt-gbuffer"), rs);
  rs.gpu = dev;
  Renderer gpu(scene, Pipeline::load("deferred-rt-gbuffer"), rs);
  const Vec3 step = (cam.lookAt - cam.position) * 0.02f + Vec3(0.05f, 0.0f, 0.0f);
  for (int f = 0; f < 3; ++f) {
    cpu.renderFrame(f, cam);
    gpu.renderFrame(f, cam);
    const std::string at = what + ", frame " + std::to_string(f);
    expectAgreement(imageAgreement(cpu.output(), gpu.output(), cpu.context().input("object_id"),
                                   gpu.context().input("object_id")),
                    at);
    for (const BufferSlot& s : gbufferSlots()) {
      const Buffer &c = cpu.context().input(s.slot), &g = gpu.context().input(s.slot);
      ASSERT_EQ(c.data.size(), g.data.size()) << at << ": " << s.slot;
      // Near-ties (imageAgreement), and the float rounding of GLSL against C++.
      EXPECT_GE(agreement(c, g, 1e-3f), 0.995) << at << ": " << s.slot;
    }
    cam.position = cam.position + step;  // the next frame's camera moved
  }
}

TEST(GpuGBuffer, TargetsAndShadingMatchTheCpu) {
  REQUIRE_GPU(dev);
  for (const char* name : {"cornell", "spheres", "atrium"}) {
    const Scene scene = loadScene(name);
    compareFrames(dev, scene, defaultCamera(scene), name);
  }
  compareFrames(dev, featureScene(), featureCamera(), "features");
  expectNoValidationMessages(*dev);
}

}  // namespace
}  // namespace tandem
