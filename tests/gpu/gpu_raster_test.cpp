// The compute rasterizer against the CPU's: raster_gbuffer's every G-buffer target and
// vbuffer_shading's image (`deferred-gbuffer`, `deferred`) on the built-in scenes and the feature
// scene (alpha masks, textures, a double-sided plane) over three frames of a moving camera, both
// eyes of a stereo frame, the rasterizer's counters, and vbuffer_shading writing only what is read;
// and the graphics pipeline's visibility draw against the CPU's the same way.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "gpu/feature_scene.h"
#include "gpu/gpu_test_util.h"
#include "passes/common/visible_surfaces.h"
#include "pipeline/renderer.h"
#include "raster/gbuffer.h"
#include "scene/loaders.h"
#include "scene/primitives.h"
#include "scene/scene_camera.h"

namespace tandem {
namespace {

void compareFrames(const std::shared_ptr<GpuDevice>& dev, const std::string& pipeline,
                   const Scene& scene, CameraDesc cam, const std::string& what,
                   StereoDesc stereo = {}) {
  RenderSettings rs{.width = 160, .height = 90, .stereo = stereo};
  Renderer cpu(scene, Pipeline::load(pipeline), rs);
  rs.gpu = dev;
  Renderer gpu(scene, Pipeline::load(pipeline), rs);
  const Vec3 step = (cam.lookAt - cam.position) * 0.02f + Vec3(0.05f, 0.0f, 0.0f);
  for (int f = 0; f < 3; ++f) {
    cpu.renderFrame(f, cam);
    gpu.renderFrame(f, cam);
    const std::string at = pipeline + ", " + what + ", frame " + std::to_string(f);
    const FrameContext &c = cpu.context(), &g = gpu.context();
    expectAgreement(
        imageAgreement(cpu.output(), gpu.output(), c.input("object_id"), g.input("object_id")), at);
    for (const BufferSlot& s : gbufferSlots()) {
      const Buffer &cb = c.input(s.slot), &gb = g.input(s.slot);
      ASSERT_EQ(cb.data.size(), gb.data.size()) << at << ": " << s.slot;
      // The ids agree but at near-ties of coverage (a vertex snapped to the other side of a
      // pixel centre by a last-bit difference); the rest within GLSL's rounding of C++'s.
      EXPECT_GE(agreement(cb, gb, 1e-3f), 0.995) << at << ": " << s.slot;
    }
    // The rasterizer's depth is the same plane evaluated the same way: equal to rounding.
    EXPECT_GE(agreement(c.input("depth"), g.input("depth"), 1e-6f), 0.995) << at;
    // Its counters: the same triangles in, culled, clipped and set up (to near-ties).
    for (const char* name : {RasterCounters::trianglesIn, RasterCounters::trianglesCulled,
                             RasterCounters::trianglesClipped, RasterCounters::trianglesBinned}) {
      const double want = c.counter(name, -1), got = g.counter(name, -2);
      EXPECT_GE(want, 0) << at << ": " << name;
      EXPECT_LE(std::abs(want - got), 0.002 * want + 1) << at << ": " << name;
    }
    cam.position = cam.position + step;  // the next frame's camera moved
  }
}

TEST(GpuRaster, GBufferAndShadingMatchTheCpu) {
  REQUIRE_GPU(dev);
  for (const char* pipeline : {"deferred-gbuffer", "deferred"}) {
    for (const char* name : {"cornell", "spheres", "atrium"}) {
      const Scene scene = loadScene(name);
      compareFrames(dev, pipeline, scene, defaultCamera(scene), name);
    }
    compareFrames(dev, pipeline, featureScene(), featureCamera(), "features");
  }
  expectNoValidationMessages(*dev);
}

TEST(GpuRaster, BothEyesOfAStereoFrame) {
  REQUIRE_GPU(dev);
  const Scene scene = loadScene("atrium");
  compareFrames(dev, "deferred", scene, defaultCamera(scene), "atrium stereo",
                StereoDesc{.enabled = true});
  expectNoValidationMessages(*dev);
}

// The graphics pipeline's visibility draw (`gpu_rasterizer = graphics`, there to be timed against
// the compute rasterizer) against the CPU's, as the compute one is compared: the same surfaces
// but at near-ties of coverage and depth (the hardware's own edge and depth rules), every pass on
// the GPU, mono and stereo, with alpha masks (the feature scene) and a moving camera.
void compareGraphics(const std::shared_ptr<GpuDevice>& dev, const std::string& pipeline,
                     const Scene& scene, CameraDesc cam, const std::string& what,
                     StereoDesc stereo = {}) {
  RenderSettings rs{.width = 160, .height = 90, .stereo = stereo};
  Renderer cpu(scene, Pipeline::load(pipeline), rs);
  rs.gpu = dev;
  Pipeline p = Pipeline::load(pipeline);
  const std::string pass = pipeline == "deferred" ? "vbuffer_shading" : "raster_gbuffer";
  p.setParam(pass + ".gpu_rasterizer=graphics", "test");
  Renderer gpu(scene, std::move(p), rs);
  const Vec3 step = (cam.lookAt - cam.position) * 0.02f + Vec3(0.05f, 0.0f, 0.0f);
  for (int f = 0; f < 3; ++f) {
    cpu.renderFrame(f, cam);
    const FrameTimings ft = gpu.renderFrame(f, cam);
    const std::string at = pipeline + " (graphics), " + what + ", frame " + std::to_string(f);
    int hosts = 0;
    for (const PassTiming& t : ft.passes) hosts += t.name.ends_with("/host") ? 1 : 0;
    EXPECT_EQ(size_t(hosts), gpu.pipeline().passes.size()) << at << ": a pass ran on the CPU";
    const FrameContext &c = cpu.context(), &g = gpu.context();
    const ImageAgreement a =
        imageAgreement(cpu.output(), gpu.output(), c.input("object_id"), g.input("object_id"),
                       &c.input("depth"), &g.input("depth"));
    expectAgreement(a, at);
    EXPECT_GE(agreement(c.input("object_id"), g.input("object_id"), 0.0f), 0.995) << at;
    // The hardware's depth is z / w interpolated by its own rules: near the CPU's plane.
    EXPECT_GE(agreement(c.input("depth"), g.input("depth"), 1e-4f), 0.99) << at;
    EXPECT_EQ(g.counter(RasterCounters::trianglesIn, -1), c.counter(RasterCounters::trianglesIn))
        << at;
    std::printf("%s: %.1f dB, ties %.4f\n", at.c_str(), a.psnr, a.ties);
    cam.position = cam.position + step;
  }
}

TEST(GpuRaster, GraphicsPipelineDrawsTheCpusSurfaces) {
  REQUIRE_GPU(dev);
  for (const char* pipeline : {"deferred", "deferred-gbuffer"}) {
    for (const char* name : {"cornell", "spheres", "atrium"}) {
      const Scene scene = loadScene(name);
      compareGraphics(dev, pipeline, scene, defaultCamera(scene), name);
    }
    compareGraphics(dev, pipeline, featureScene(), featureCamera(), "features");
  }
  const Scene atrium = loadScene("atrium");
  compareGraphics(dev, "deferred", atrium, defaultCamera(atrium), "atrium stereo",
                  StereoDesc{.enabled = true});
  expectNoValidationMessages(*dev);
}

// Two triangles whose pixel boxes span a 2048 x 2080 frame, 66560 tiles of 8x8 each: drawn by
// raster_queue in bands of rows. Drawn a workgroup a triangle, lavapipe (which ends a loop after
// 65535 iterations) left the last rows of each unwritten: the sky showed through.
TEST(GpuRaster, LargeTrianglesEqualTheCpus) {
  REQUIRE_GPU(dev);
  Scene scene;
  Material grey;
  grey.diffuse = {0.5f, 0.5f, 0.5f};
  Transform wall;
  wall.rotationDeg = {90, 0, 0};  // the plane's normal +y turned to face the camera on +z
  wall.scale = {50, 1, 50};
  scene.addObject("wall", scene.addMesh(makePlane()), scene.addMaterial(grey), wall);
  CameraDesc cam;
  cam.position = {0, 0, 5};
  cam.lookAt = {0, 0, 0};
  RenderSettings rs{.width = 2048, .height = 2080};
  Renderer cpu(scene, Pipeline::load("deferred-gbuffer"), rs);
  rs.gpu = dev;
  Renderer gpu(scene, Pipeline::load("deferred-gbuffer"), rs);
  cpu.renderFrame(0, cam);
  gpu.renderFrame(0, cam);
  const Buffer &c = cpu.context().input("object_id"), &g = gpu.context().input("object_id");
  size_t covered = 0;
  for (float id : c.data) covered += id == 0.0f ? 1 : 0;
  EXPECT_GE(double(covered), 0.99 * double(c.pixelCount())) << "the wall fills the CPU's frame";
  ASSERT_EQ(c.data.size(), g.data.size());
  size_t differ = 0;
  for (size_t i = 0; i < c.data.size(); ++i) differ += c.data[i] != g.data[i] ? 1 : 0;
  EXPECT_EQ(differ, 0u) << "pixels whose object differs";
  expectNoValidationMessages(*dev);
}

// vbuffer_shading writes a G-buffer target only when something reads it; the image is the same
// whether all are read or none.
TEST(GpuRaster, VBufferShadingWritesOnlyWhatIsRead) {
  REQUIRE_GPU(dev);
  const Scene scene = featureScene();
  RenderSettings rs{.width = 160, .height = 90, .gpu = dev};
  Renderer all(scene, Pipeline::load("deferred"), rs), lean(scene, Pipeline::load("deferred"), rs);
  lean.context().keepAllOutputs = false;
  lean.context().wanted = {"object_id"};
  all.renderFrame(0, featureCamera());
  lean.renderFrame(0, featureCamera());
  const Buffer &a = all.output(), &b = lean.output();
  ASSERT_EQ(a.data.size(), b.data.size());
  EXPECT_EQ(std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)), 0);
  EXPECT_EQ(lean.context().input("object_id").data, all.context().input("object_id").data);
  EXPECT_FALSE(lean.context().buffers.count("normal"));
  EXPECT_FALSE(lean.context().buffers.count("diffuse"));
  expectNoValidationMessages(*dev);
}

}  // namespace
}  // namespace tandem
