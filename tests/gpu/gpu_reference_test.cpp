// `tandem reference` on the GPU against the CPU: the path tracer (cornell, its emissive lamp
// sampled as an area light) at 256 spp, and distributed Whitted ray tracing through a thin lens
// (spheres) at 64 spp, and the foveated pipelines' diffuse global illumination (lights picked by
// the light grid; cornell and the feature scene's every light type) at 256 spp; then an open
// shutter: objects and the camera moving through it with a lens (Whitted), and a glowing ball
// flying through the Cornell box (path tracing, the ball an area light where it is at each
// sample's time). Both devices take the same Sobol samples, so the GPU image must lie at least as
// near the CPU's as a CPU image with another seed does (within 1.5x its RMSE).
#include <gtest/gtest.h>

#include <algorithm>

#include "eval/metrics/metrics.h"
#include "eval/reference/reference_cache.h"
#include "gpu/feature_scene.h"
#include "gpu/gpu_test_util.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {
namespace {

double mean(const Buffer& b) {
  double sum = 0;
  for (float v : b.data) sum += v;
  return sum / double(std::max<size_t>(b.data.size(), 1));
}

// A still camera and shutter, or (shutter > 0) the camera at shutter close.
struct Shutter {
  float seconds = 0;
  CameraDesc close;
};

ReferenceImage render(const Scene& scene, CameraDesc cam, Integrator integrator, int spp,
                      uint64_t seed, std::shared_ptr<GpuDevice> gpu, const Shutter& shutter) {
  ReferenceJob job;
  job.scene = &scene;
  job.camera = cam;
  job.shutterCamera = shutter.seconds > 0 ? shutter.close : cam;
  job.shutter = shutter.seconds;
  job.width = 48;
  job.height = 27;
  job.settings.spp = spp;
  job.settings.integrator = integrator;
  job.settings.seed = seed;
  job.gpu = std::move(gpu);
  return referenceImage(job, "", nullptr);
}

void expectConverges(const std::shared_ptr<GpuDevice>& dev, const Scene& scene, CameraDesc cam,
                     Integrator integrator, int spp, const std::string& what,
                     const Shutter& shutter = {}) {
  const ReferenceImage cpu = render(scene, cam, integrator, spp, 1, nullptr, shutter);
  const ReferenceImage other = render(scene, cam, integrator, spp, 2, nullptr, shutter);
  const ReferenceImage gpu = render(scene, cam, integrator, spp, 1, dev, shutter);
  EXPECT_EQ(gpu.spp, spp) << what;
  EXPECT_GT(gpu.rays, uint64_t(48 * 27 * spp)) << what;  // every sample traced at least its ray
  const double noise = rmse(cpu.hdr, other.hdr), gap = rmse(cpu.hdr, gpu.hdr);
  EXPECT_GT(noise, 0.0) << what;
  EXPECT_LE(gap, 1.5 * noise) << what << ": GPU-vs-CPU " << gap << ", CPU seeds " << noise;
  // The same mean (an estimator of the same light transport): within 1 %.
  EXPECT_NEAR(mean(gpu.hdr), mean(cpu.hdr), 0.01 * mean(cpu.hdr)) << what;
}

TEST(GpuReference, PathTracerConvergesToTheCpus) {
  REQUIRE_GPU(dev);
  const Scene cornell = loadScene("cornell");
  expectConverges(dev, cornell, defaultCamera(cornell), Integrator::Path, 256, "cornell, path");
  expectNoValidationMessages(*dev);
}

TEST(GpuReference, WhittedThroughAThinLensConvergesToTheCpus) {
  REQUIRE_GPU(dev);
  const Scene spheres = loadScene("spheres");
  CameraDesc cam = defaultCamera(spheres);
  cam.apertureDiameter = 0.2f;
  cam.focusDistance = length(cam.lookAt - cam.position);
  cam.apertureBlades = 6;
  expectConverges(dev, spheres, cam, Integrator::Whitted, 64, "spheres, whitted, thin lens");
  expectNoValidationMessages(*dev);
}

TEST(GpuReference, DiffuseGIConvergesToTheCpus) {
  REQUIRE_GPU(dev);
  const Scene cornell = loadScene("cornell");
  expectConverges(dev, cornell, defaultCamera(cornell), Integrator::DiffuseGI, 256,
                  "cornell, diffuse-gi");
  expectConverges(dev, featureScene(), featureCamera(), Integrator::DiffuseGI, 256,
                  "features, diffuse-gi");
  expectNoValidationMessages(*dev);
}

Scene repoScene(const std::string& name) {
  return loadScene(std::string(TANDEM_SOURCE_DIR) + "/scenes/" + name + ".json");
}

TEST(GpuReference, WhittedThroughAnOpenShutterConvergesToTheCpus) {
  REQUIRE_GPU(dev);
  // Both objects move in the shutter's 0.1 s (the ball 3.6 m), and the camera pans, with a lens.
  const Scene both = repoScene("interleaved_both");
  const CameraDesc open = pathCameraAt(both, defaultCamera(both), 0.0f);
  const Shutter shutter{0.1f, pathCameraAt(both, defaultCamera(both), 0.1f)};
  ASSERT_NE(open.position.x, shutter.close.position.x);
  expectConverges(dev, both, open, Integrator::Whitted, 64, "interleaved_both, whitted, shutter",
                  shutter);
  expectNoValidationMessages(*dev);
}

TEST(GpuReference, PathTracerThroughAnOpenShutterConvergesToTheCpus) {
  REQUIRE_GPU(dev);
  const Scene cornell = repoScene("cornell_motion_blur");
  const CameraDesc cam = defaultCamera(cornell);
  expectConverges(dev, cornell, cam, Integrator::Path, 128, "cornell_motion_blur, path, shutter",
                  {0.5f, cam});
  expectNoValidationMessages(*dev);
}

}  // namespace
}  // namespace tandem
