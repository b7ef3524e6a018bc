// Interleaved sampling (Foster 2015; Fatahalian et al. 2009) on the GPU against the CPU:
// interleaved_rt and interleaved_raster (the compute rasterizer in sample mode) run on both
// devices from the same frame (the same pairs, tiles and sample layout), for motion blur over an
// open shutter (moving objects drawn and traced at each pair's time), defocus, both, with the
// schemes, filters, shading and shading rate switched, a sample mask, and the velocity, view depth
// and motion buffers the post-process blur and TAA read; the motion-blur pipelines on the GPU
// whole; the accumulation baselines.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gpu/gpu_test_util.h"
#include "pipeline/gpu_frame.h"
#include "pipeline/renderer.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {
namespace {

struct Case {
  std::string pipeline, scene, what;
  std::vector<std::string> params;
  bool masked = false;
  std::string output = "hdr";  // "motion": something reads the motion buffer
};

void compare(const std::shared_ptr<GpuDevice>& dev, const Case& k) {
  const Scene scene = loadScene(std::string(TANDEM_SOURCE_DIR) + "/scenes/" + k.scene + ".json");
  RenderSettings rs{.width = 64, .height = 36};
  rs.shutter = 0.1f;
  const auto load = [&] {
    Pipeline p = Pipeline::load(k.pipeline);
    for (const std::string& q : k.params) p.setParam(q, "test");
    Pipeline alone;
    alone.name = k.pipeline + ": its first pass alone";
    alone.passes.push_back(std::move(p.passes.front()));
    alone.output = k.output;
    return alone;
  };
  // Two frames on the CPU (the camera path moving: last frame's camera for the motion buffer).
  Renderer cpu(scene, Pipeline::load(k.pipeline), rs);
  CameraDesc cam = defaultCamera(scene);
  cpu.renderFrame(0, cam);
  cam.position = cam.position + Vec3(0.02f, 0.0f, 0.01f);
  cpu.renderFrame(1, cam);
  const FrameContext& from = cpu.context();
  FrameContext runs[2];
  for (int onGpu = 0; onGpu < 2; ++onGpu) {
    FrameContext& ctx = runs[onGpu];
    ctx = frameAgain(from, onGpu ? dev : nullptr);
    ctx.buffers.clear();  // the pass reads none but the mask
    if (k.masked) {       // a disc of pixels where the samples are wanted
      Buffer mask(ctx.width, ctx.height, 1, 0.0f, BufferKind::Mask);
      for (int y = 0; y < ctx.height; ++y)
        for (int x = 0; x < ctx.width; ++x)
          mask.at(x, y)[0] = std::hypot(x - 30.0f, y - 18.0f) < 12.0f ? 1.0f : 0.0f;
      ctx.buffers["sample_mask"] = mask;
    }
    Pipeline p = load();
    const FrameTimings ft = p.execute(ctx);
    size_t hosts = 0;
    for (const PassTiming& t : ft.passes) hosts += t.name.ends_with("/host") ? 1 : 0;
    EXPECT_EQ(hosts, onGpu ? 1u : 0u) << k.what << ": the pass did not run on the GPU";
  }
  const FrameContext &c = runs[0], &g = runs[1];
  for (const char* name : {"hdr", "velocity", "view_depth", "motion"}) {
    if (!c.buffers.count(name)) continue;
    const Buffer &cb = c.input(name), &gb = g.input(name);
    ASSERT_TRUE(cb.sameShape(gb)) << k.what << ": " << name;
    for (float v : gb.data) ASSERT_TRUE(std::isfinite(v)) << k.what << ": " << name;
    // The same rays from the same samples: equal but for rounding, and where a ray passes
    // within rounding of two surfaces (a sample near an edge) Embree and the GPU may each take
    // another (a few pixels). view_depth is 1e30 on the sky: compared relatively.
    const double same = agreement(cb, gb, 1e-3f);
    EXPECT_GE(same, 0.98) << k.what << ": " << name;
    if (std::string(name) != "view_depth") {
      const double db = psnr(cb, gb, 1.0);
      EXPECT_GE(db, 45.0) << k.what << ": " << name;
      std::printf("%s: %s %.1f dB, %.2f %% agree\n", k.what.c_str(), name, db, 100 * same);
    }
  }
  // Something moved: the velocities compared are not all zero.
  if (k.scene != "interleaved_defocus") {
    float most = 0;
    for (float v : c.input("velocity").data) most = std::max(most, std::abs(v));
    EXPECT_GT(most, 0.5f) << k.what << ": velocity";
  }
  if (k.masked) {  // outside the mask nothing is resolved
    const Buffer& h = g.input("hdr");
    EXPECT_EQ(h.at(2, 2)[0], 0.0f) << k.what;
  }
  const std::string type =
      k.pipeline == "interleaved-rt" ? "interleaved_rt/" : "interleaved_raster/";
  for (const std::string q :
       {"passes", "samples_per_pixel", "shadow_traced", "min_similar_time_distance_px"}) {
    const double cv = c.counter(type + q, -1);
    if (cv == -1) continue;
    EXPECT_NEAR(g.counter(type + q, -2), cv, 0.01 * std::abs(cv) + 1e-6) << k.what << ": " << q;
  }
}

// interleaved_rt and interleaved_raster from the same frame: each its own test (CTest runs them
// side by side; each takes minutes on lavapipe).
TEST(GpuInterleaved, InterleavedRtMatchesTheCpu) {
  REQUIRE_GPU(dev);
  const std::string rt = "interleaved-rt";
  const std::vector<Case> cases = {
      {rt, "interleaved_motion", "rt: motion blur, colored-corner tiles", {}},
      {rt,
       "interleaved_defocus",
       "rt: defocus, Blackman-Harris filter",
       {"interleaved_rt.filter=blackman_harris", "interleaved_rt.filter_radius=1.5"}},
      {rt,
       "interleaved_both",
       "rt: both, stratified, local shading",
       {"interleaved_rt.scheme=stratified", "interleaved_rt.shading=local"}},
      {rt,
       "interleaved_motion",
       "rt: a sample mask, the motion buffer read",
       {"interleaved_rt.samples=8", "interleaved_rt.spp=2"},
       true,
       "motion"},
      {rt,
       "interleaved_motion",
       "rt: a sharp image shaded once a pixel and surface (the samples traced first)",
       {"interleaved_rt.mode=motion_blur", "interleaved_rt.shutter_time=0.5",
        "interleaved_rt.shading_rate=pixel"}},
  };
  for (const Case& k : cases) compare(dev, k);
  expectNoValidationMessages(*dev);
}

TEST(GpuInterleaved, InterleavedRasterMatchesTheCpu) {
  REQUIRE_GPU(dev);
  const std::string raster = "interleaved-raster";
  const std::vector<Case> cases = {
      {raster,
       "interleaved_motion",
       "raster: motion blur (moving objects drawn at each pass's time)",
       {}},
      {raster,
       "interleaved_both",
       "raster: both, random tiles, Blackman-Harris",
       {"interleaved_raster.scheme=random_tiles", "interleaved_raster.filter=blackman_harris"}},
      {raster,
       "interleaved_motion",
       "raster: a sharp image shaded once a pixel and surface (MSAA-style)",
       {"interleaved_raster.mode=motion_blur", "interleaved_raster.shutter_time=0.5",
        "interleaved_raster.shading_rate=pixel"}},
      {raster,
       "interleaved_motion",
       "raster: a sample mask, the motion buffer read",
       {"interleaved_raster.samples=8", "interleaved_raster.spp=2"},
       true,
       "motion"},
  };
  for (const Case& k : cases) compare(dev, k);
  expectNoValidationMessages(*dev);
}

// The motion-blur pipelines on the GPU whole over two frames (TAA's history kept on the device):
// the CPU's image.
TEST(GpuInterleaved, MotionBlurPipelinesRunOnTheGpuWhole) {
  REQUIRE_GPU(dev);
  const Scene scene = loadScene(std::string(TANDEM_SOURCE_DIR) + "/scenes/interleaved_motion.json");
  for (const char* pipeline : {"postfx-motion-blur", "hybrid-motion-blur"}) {
    RenderSettings rs{.width = 64, .height = 36};
    rs.shutter = 0.1f;
    Renderer cpu(scene, Pipeline::load(pipeline), rs);
    rs.gpu = dev;
    Renderer gpu(scene, Pipeline::load(pipeline), rs);
    for (int f = 0; f < 2; ++f) {
      const std::string at = std::string(pipeline) + ", frame " + std::to_string(f);
      cpu.renderFrame(f, defaultCamera(scene));
      const FrameTimings ft = gpu.renderFrame(f, defaultCamera(scene));
      size_t hosts = 0;
      for (const PassTiming& t : ft.passes) hosts += t.name.ends_with("/host") ? 1 : 0;
      EXPECT_EQ(hosts, gpu.pipeline().passes.size()) << at << ": a pass ran on the CPU";
      const Buffer &c = cpu.context().input("hdr"), &g = gpu.context().input("hdr");
      EXPECT_GE(psnr(c, g, 1.0), 45.0) << at;
      EXPECT_GE(agreement(c, g, 1e-3f), 0.99) << at;
    }
  }
  expectNoValidationMessages(*dev);
}

// The accumulation baselines on the GPU whole (the compute rasterizer at each pair's time and lens
// point, the scene moved between pairs): the CPU's image.
TEST(GpuInterleaved, AccumulationMatchesTheCpu) {
  REQUIRE_GPU(dev);
  const Scene scene = loadScene(std::string(TANDEM_SOURCE_DIR) + "/scenes/interleaved_both.json");
  for (const char* pipeline : {"accumulation-dof", "accumulation-motion-blur"}) {
    for (const char* shading : {"whitted", "local"}) {
      const std::string at = std::string(pipeline) + ", " + shading;
      RenderSettings rs{.width = 64, .height = 36};
      rs.shutter = 0.1f;
      const auto load = [&] {
        Pipeline p = Pipeline::load(pipeline);
        p.setParam("accumulation.samples=8", "test");
        p.setParam(std::string("accumulation.shading=") + shading, "test");
        return p;
      };
      Renderer cpu(scene, load(), rs);
      rs.gpu = dev;
      Renderer gpu(scene, load(), rs);
      cpu.renderFrame(0, defaultCamera(scene));
      const FrameTimings ft = gpu.renderFrame(0, defaultCamera(scene));
      size_t hosts = 0;
      for (const PassTiming& t : ft.passes) hosts += t.name.ends_with("/host") ? 1 : 0;
      EXPECT_EQ(hosts, gpu.pipeline().passes.size()) << at << ": a pass ran on the CPU";
      const Buffer &c = cpu.context().input("hdr"), &g = gpu.context().input("hdr");
      const double db = psnr(c, g, 1.0);
      EXPECT_GE(db, 45.0) << at;
      EXPECT_GE(agreement(c, g, 1e-3f), 0.99) << at;
      EXPECT_EQ(gpu.context().counter("accumulation/triangles_binned", -1),
                cpu.context().counter("accumulation/triangles_binned", -2))
          << at;
      std::printf("%s: hdr %.1f dB\n", at.c_str(), db);
    }
  }
  expectNoValidationMessages(*dev);
}

}  // namespace
}  // namespace tandem
