// The shadow maps the GPU draws (depth maps by the compute rasterizer, conservative maps by
// conservative_depth.comp, the opaque casters' depth) against the CPU's, texel by texel: after the
// first frame (every face drawn anew) and after frames in which an animated caster moved (the
// static casters' copy restored where it was and is, and the caster drawn over it).
#include <gtest/gtest.h>

#include <cmath>

#include "gpu/gpu_test_util.h"
#include "passes/common/gpu_shadow_maps.h"
#include "pipeline/renderer.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {
namespace {

constexpr int kMapSize = 256;
// The size whose sun face (twice the side, 2048 texels) holds triangles of a million texels:
// queued in bands, as lavapipe ends a loop after 65535 iterations (the balcony slabs' tops were
// lost before).
constexpr int kLargeMapSize = 1024;

// The share of texels where a and b agree to `tol` (relative to 1).
double sameShare(const float* a, const std::vector<float>& b, float tol) {
  size_t same = 0;
  for (size_t i = 0; i < b.size(); ++i) same += std::abs(a[i] - b[i]) <= tol ? 1 : 0;
  return double(same) / double(std::max<size_t>(b.size(), 1));
}

void compareMaps(const ShadowMaps& cpu, const ShadowMaps& gpu, const std::string& at) {
  ASSERT_EQ(cpu.lights(), gpu.lights()) << at;
  EXPECT_EQ(cpu.mappedLights(), gpu.mappedLights()) << at;
  EXPECT_GT(gpu.mappedLights(), 0) << at;
  for (size_t i = 0; i < cpu.lights(); ++i) {
    const auto cf = cpu.faceViews(i), gf = gpu.faceViews(i);
    ASSERT_EQ(cf.size(), gf.size()) << at << ", light " << i;
    for (size_t k = 0; k < cf.size(); ++k) {
      const std::string face = at + ", light " + std::to_string(i) + " face " + std::to_string(k);
      const DeviceShadowFace d = readDeviceShadowFace(gpu, i, k);
      ASSERT_EQ(d.width, cf[k].width) << face;
      ASSERT_EQ(d.height, cf[k].height) << face;
      const size_t n = d.depth.size();
      // The depth map: the same set-up and plane as the CPU's rasterizer, equal but at
      // near-ties of coverage (a last-bit difference in a snapped vertex).
      EXPECT_GE(sameShare(cf[k].depth, d.depth, 1e-6f), 0.999) << face << ": depth";
      EXPECT_GE(sameShare(cf[k].opaqueDepth, d.opaque, 1e-6f), 0.999) << face << ": opaque";
      // The conservative map: the same object nearest in each texel, at the same depth.
      size_t same = 0, touched = 0;
      for (size_t t = 0; t < n; ++t) {
        const ConservativeDepth::Texel &c = cf[k].near[t], &g = d.near[t];
        touched += c.object != kNoObject ? 1 : 0;
        same += c.object == g.object && std::abs(c.depth - g.depth) <= 1e-6f ? 1 : 0;
      }
      EXPECT_GE(double(same) / double(n), 0.999) << face << ": conservative";
      if (k == 0) {
        EXPECT_GT(touched, n / 100) << face << ": the map holds (almost) nothing";
      }
    }
  }
}

// `moving`: the scene has an animated caster, drawn again over the static copy after frame 0.
void compareScene(const std::shared_ptr<GpuDevice>& dev, const std::string& name, int frames,
                  bool moving, int mapSize = kMapSize) {
  const Scene scene = loadScene(name);
  RenderSettings rs{.width = 96, .height = 54};
  const auto load = [mapSize] {
    Pipeline p = Pipeline::load("rt-only");
    p.setParam("rt_whitted.shadows=classified", "test");
    p.setParam("rt_whitted.shadow_map_size=" + std::to_string(mapSize), "test");
    return p;
  };
  Renderer cpu(scene, load(), rs);
  rs.gpu = dev;
  Renderer gpu(scene, load(), rs);
  const CameraDesc cam = defaultCamera(scene);
  for (int f = 0; f < frames; ++f) {
    cpu.renderFrame(f * 8, cam);  // the animated sphere moves between these frames
    gpu.renderFrame(f * 8, cam);
    const ShadowMaps* c = cpu.context().heldShadowMaps(mapSize, false);
    const ShadowMaps* g = gpu.context().heldShadowMaps(mapSize, true);
    ASSERT_TRUE(c && g) << name;
    ASSERT_TRUE(g->device()) << name;
    compareMaps(*c, *g, name + ", frame " + std::to_string(f));
    EXPECT_EQ(c->movingRedraws(), g->movingRedraws()) << name;
    if (moving && f > 0) {
      EXPECT_GT(g->movingRedraws(), 0) << name;
    }
  }
}

TEST(GpuShadowMaps, DeviceMapsEqualTheCpus) {
  REQUIRE_GPU(dev);
  compareScene(dev, "spheres", 3, true);  // a sun, two point lights' cubes, a moving caster
  compareScene(dev, "atrium", 1, false);  // a spot light besides
  expectNoValidationMessages(*dev);
}

TEST(GpuShadowMaps, LargeFacesEqualTheCpus) {
  REQUIRE_GPU(dev);
  const Scene atrium = loadScene("atrium");
  const Light& sun = atrium.lights[0];
  ASSERT_EQ(sun.type, LightType::Directional);
  ASSERT_EQ(shadowFaceSize(sun, kLargeMapSize), 2048);
  compareScene(dev, "atrium", 1, false, kLargeMapSize);
  expectNoValidationMessages(*dev);
}

}  // namespace
}  // namespace tandem
