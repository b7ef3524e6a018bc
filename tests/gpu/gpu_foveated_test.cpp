// Peres 2022's foveated stereo path tracing on the GPU against the CPU: foveation (the
// distribution, moved to the device), foveated_pt, direct_light, periphery_accumulation and
// nh_denoise, each given the same inputs on both devices (the buffers a CPU frame of the pipeline
// left), in Base, NH2LD, NH3LD and the temporal NH3LD, with the settings switched; and the
// pipelines on the GPU whole over 16 frames of a moving camera, both eyes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>

#include "gpu/gpu_test_util.h"
#include "pipeline/gpu_frame.h"
#include "pipeline/renderer.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {
namespace {

const std::set<std::string> kFoveatedPasses = {"foveation", "foveated_pt", "direct_light",
                                               "periphery_accumulation", "nh_denoise"};

Scene pinkRoom() {
  return loadScene(std::string(TANDEM_SOURCE_DIR) + "/scenes/foveated_pink_room.json");
}

RenderSettings stereoSettings(int width, int height) {
  RenderSettings rs{.width = width, .height = height};
  rs.stereo.enabled = true;
  return rs;
}

Pipeline loadWith(const std::string& pipeline, const std::vector<std::string>& params) {
  Pipeline p = Pipeline::load(pipeline);
  for (const std::string& q : params) p.setParam(q, "test");
  return p;
}

// The pipeline's foveated passes (with `params`), alone.
Pipeline foveatedPasses(const std::string& pipeline, const std::vector<std::string>& params) {
  Pipeline full = loadWith(pipeline, params);
  Pipeline p;
  p.name = pipeline + " (foveated passes)";
  for (auto& pass : full.passes)
    if (kFoveatedPasses.count(pass->type())) {
      p.output = pass->bufferName("denoised");
      p.passes.push_back(std::move(pass));
    }
  return p;
}

// The passes run again from `from`'s buffers (on the GPU with `dev`), with seed `seed`.
FrameContext runAgain(const FrameContext& from, const std::string& pipeline,
                      const std::vector<std::string>& params, const std::shared_ptr<GpuDevice>& dev,
                      uint64_t seed) {
  FrameContext ctx = frameAgain(from, dev);  // the same frame again (its samples)
  ctx.seed = seed;
  Pipeline p = foveatedPasses(pipeline, params);
  for (const auto& pass : p.passes)  // what the passes write, written anew
    for (const BufferSlot& o : pass->outputs()) ctx.buffers.erase(pass->bufferName(o.slot));
  const FrameTimings ft = p.execute(ctx);
  size_t hosts = 0;
  for (const PassTiming& t : ft.passes) hosts += t.name.ends_with("/host") ? 1 : 0;
  EXPECT_EQ(hosts, dev ? p.passes.size() : 0u) << pipeline << ": a pass did not run on the GPU";
  return ctx;
}

// Two CPU frames of `pipeline` (the camera moving); then its foveated passes run again from the
// second frame's buffers, on the CPU and on the GPU, and their outputs compared.
void comparePasses(const std::shared_ptr<GpuDevice>& dev, const std::string& pipeline,
                   const std::string& what, const std::vector<std::string>& params = {}) {
  const Scene scene = pinkRoom();
  CameraDesc cam = defaultCamera(scene);
  Renderer cpu(scene, loadWith(pipeline, params), stereoSettings(80, 60));
  for (int f = 0; f < 2; ++f) {
    cpu.renderFrame(f, cam);
    cam.position = cam.position + Vec3(0.03f, 0.0f, 0.01f);
  }
  const FrameContext& from = cpu.context();
  const FrameContext c = runAgain(from, pipeline, params, nullptr, from.seed);
  const FrameContext g = runAgain(from, pipeline, params, dev, from.seed);
  const std::string at = pipeline + ", " + what;
  // The distribution and the masks: exact.
  for (const char* name : {"fov_coords", "fov_mask", "fov_layer"}) {
    ASSERT_TRUE(c.input(name).sameShape(g.input(name))) << at << ": " << name;
    EXPECT_EQ(c.input(name).data, g.input(name).data) << at << ": " << name;
  }
  if (c.buffers.count("pt_accum_mask")) {
    EXPECT_EQ(c.input("pt_accum_mask").data, g.input("pt_accum_mask").data) << at;
  }
  // The same samples of the same paths on both devices: where a ray passes within rounding of two
  // surfaces Embree and the GPU's traversal may each take another (a few pixels).
  for (const char* name :
       {"pt_noisy", "pt_variance", "pt_direct", "pt_accum", "pt_accum_variance", "denoised"}) {
    if (!c.buffers.count(name)) continue;
    const Buffer &cb = c.input(name), &gb = g.input(name);
    ASSERT_TRUE(cb.sameShape(gb)) << at << ": " << name;
    for (float v : gb.data) ASSERT_TRUE(std::isfinite(v)) << at << ": " << name;
    const double db = psnr(cb, gb, 1.0);
    EXPECT_GE(db, 45.0) << at << ": " << name;
    EXPECT_GE(agreement(cb, gb, 1e-3f), 0.99) << at << ": " << name;
    testing::Test::RecordProperty(at + ": " + name + " dB", std::to_string(db));
    std::printf("%s: %s %.1f dB\n", at.c_str(), name, db);
  }
  // The path tracer's error against the CPU's, within 1.5x of the CPU's own with another seed
  // (and the same mean).
  const FrameContext other = runAgain(from, pipeline, params, nullptr, from.seed + 1);
  const double gpuError = rmse(c.input("pt_noisy"), g.input("pt_noisy"));
  const double seedError = rmse(c.input("pt_noisy"), other.input("pt_noisy"));
  EXPECT_LE(gpuError, 1.5 * seedError) << at;
  double cm = 0, gm = 0;
  for (size_t i = 0; i < c.input("pt_noisy").data.size(); ++i)
    cm += c.input("pt_noisy").data[i], gm += g.input("pt_noisy").data[i];
  EXPECT_NEAR(gm, cm, 0.005 * std::abs(cm)) << at << ": mean";
  for (const char* q :
       {"foveation/listed", "foveation/samples", "foveated_pt/samples", "nh_denoise/levels_run",
        "nh_denoise/levels_region0", "nh_denoise/levels_region1", "nh_denoise/levels_region2"}) {
    const double cv = c.counter(q, -1);
    if (cv == -1) continue;
    EXPECT_EQ(g.counter(q, -2), cv) << at << ": " << q;
  }
  const double frames = c.counter("periphery_accumulation/mean_frames", -1);
  if (frames != -1) {
    EXPECT_NEAR(g.counter("periphery_accumulation/mean_frames", -2), frames, 0.01 * frames) << at;
  }
}

TEST(GpuFoveated, PassesMatchTheCpuOnTheSameInputs) {
  REQUIRE_GPU(dev);
  comparePasses(dev, "foveated-nh3ld", "NH3LD");
  comparePasses(dev, "foveated-base", "Base (every pixel, one region)");
  comparePasses(dev, "foveated-nh2ld", "NH2LD, the whole estimate filtered, uniform lights",
                {"nh_denoise.split=none", "foveated_pt.light_selection=uniform"});
  comparePasses(dev, "foveated-nh3ld", "levels from the noise, no demodulation",
                {"nh_denoise.levels_from=variance", "nh_denoise.demodulate=false"});
  comparePasses(dev, "foveated-nh3ld", "the variance colour weight (its prefilters, the guide)",
                {"nh_denoise.color_weight=variance"});
  comparePasses(dev, "foveated-nh3ld-temporal", "temporal, with history",
                {"direct_light.lights=1"});
  expectNoValidationMessages(*dev);
}

// The foveated pipelines on the GPU whole, both eyes, over 16 frames of a moving camera (the
// periphery's history kept on the device): PSNR >= 45 dB where both saw the same surface.
void compareWhole(const std::shared_ptr<GpuDevice>& dev, const std::string& pipeline, int frames) {
  const Scene scene = pinkRoom();
  CameraDesc cam = defaultCamera(scene);
  RenderSettings rs = stereoSettings(160, 90);
  Renderer cpu(scene, Pipeline::load(pipeline), rs);
  rs.gpu = dev;
  Renderer gpu(scene, Pipeline::load(pipeline), rs);
  for (int f = 0; f < frames; ++f) {
    const std::string at = pipeline + ", frame " + std::to_string(f);
    cpu.renderFrame(f, cam);
    const FrameTimings ft = gpu.renderFrame(f, cam);
    size_t hosts = 0;
    for (const PassTiming& t : ft.passes) hosts += t.name.ends_with("/host") ? 1 : 0;
    EXPECT_EQ(hosts, gpu.pipeline().passes.size()) << at << ": a pass ran on the CPU";
    const FrameContext &c = cpu.context(), &g = gpu.context();
    // The sofa's seat and arms share faces: where two objects meet at the same depth either wins.
    expectAgreement(imageAgreement(cpu.output(), gpu.output(), c.input("object_id"),
                                   g.input("object_id"), &c.input("depth"), &g.input("depth")),
                    at);
    cam.position = cam.position + Vec3(0.02f, 0.0f, 0.01f);
  }
}

TEST(GpuFoveated, PipelinesRunOnTheGpuWhole) {
  REQUIRE_GPU(dev);
  compareWhole(dev, "foveated-nh3ld-temporal", 16);
  compareWhole(dev, "foveated-base", 2);
  compareWhole(dev, "foveated-nh3ld-raster", 2);
  expectNoValidationMessages(*dev);
}

}  // namespace
}  // namespace tandem
