// The motion blur's image-space passes on the GPU against the CPU: postfx_motion_blur (McGuire
// et al. 2012's tiles, neighbourhoods and gather, and the hybrid's mask of mixed motion) and
// mb_composite, given the same inputs on both devices (the buffers a CPU frame of
// `hybrid-motion-blur` left), with the mask's two rules and another tile size and sample count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gpu/gpu_test_util.h"
#include "pipeline/gpu_frame.h"
#include "pipeline/renderer.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {
namespace {

void comparePasses(const std::shared_ptr<GpuDevice>& dev, const std::string& what,
                   const std::vector<std::string>& params = {}) {
  const Scene scene = loadScene(std::string(TANDEM_SOURCE_DIR) + "/scenes/interleaved_motion.json");
  RenderSettings rs{.width = 160, .height = 90};
  rs.shutter = 0.1f;
  const auto load = [&] {
    Pipeline p = Pipeline::load("hybrid-motion-blur");
    for (const std::string& q : params) p.setParam(q, "test");
    return p;
  };
  Renderer cpu(scene, load(), rs);
  cpu.renderFrame(0, defaultCamera(scene));
  const FrameContext& from = cpu.context();
  FrameContext runs[2];
  for (int onGpu = 0; onGpu < 2; ++onGpu) {
    FrameContext& ctx = runs[onGpu];
    ctx = frameAgain(from, onGpu ? dev : nullptr);
    Pipeline full = load(), p;
    p.name = "motion blur passes";
    for (auto& pass : full.passes)
      if (pass->type() == "postfx_motion_blur" || pass->type() == "mb_composite")
        p.passes.push_back(std::move(pass));
    p.output = p.passes.back()->bufferName("hdr");
    for (const auto& pass : p.passes)
      for (const BufferSlot& o : pass->outputs()) ctx.buffers.erase(pass->bufferName(o.slot));
    const FrameTimings ft = p.execute(ctx);
    size_t hosts = 0;
    for (const PassTiming& t : ft.passes) hosts += t.name.ends_with("/host") ? 1 : 0;
    EXPECT_EQ(hosts, onGpu ? p.passes.size() : 0u) << what << ": a pass did not run on the GPU";
  }
  const FrameContext &c = runs[0], &g = runs[1];
  // Something to blur and to mask: the test is not of a still image.
  const double masked = c.counter("postfx_motion_blur/masked_tiles_percent", -1);
  EXPECT_GT(masked, 0.0) << what;
  EXPECT_NEAR(g.counter("postfx_motion_blur/masked_tiles_percent", -2), masked, 1e-9) << what;
  EXPECT_EQ(c.input("mb_mask").data, g.input("mb_mask").data) << what;
  for (const char* name : {"mb_postfx", "hdr"}) {
    const Buffer &cb = c.input(name), &gb = g.input(name);
    ASSERT_TRUE(cb.sameShape(gb)) << what << ": " << name;
    for (float v : gb.data) ASSERT_TRUE(std::isfinite(v)) << what << ": " << name;
    // A deterministic pass: all but 0.1 % of the pixels within 1e-3 (GLSL's sqrt and divisions
    // round as C++'s or within an ulp).
    const double db = psnr(cb, gb, 1.0);
    EXPECT_GE(db, 45.0) << what << ": " << name;
    EXPECT_GE(agreement(cb, gb, 1e-3f), 0.999) << what << ": " << name;
    std::printf("%s: %s %.1f dB\n", what.c_str(), name, db);
  }
  // The blur changed the sharp image (a gather that did nothing would pass the above).
  EXPECT_LT(psnr(c.input("sharp"), c.input("mb_postfx"), 1.0), 60.0) << what;
}

TEST(GpuMotionBlur, PassesMatchTheCpuOnTheSameInputs) {
  REQUIRE_GPU(dev);
  comparePasses(dev, "mask of velocity jumps (the pipeline's)");
  comparePasses(dev, "mask of spread motion", {"postfx_motion_blur.mask=spread"});
  comparePasses(dev, "8-pixel tiles, 7 samples, a lower threshold",
                {"postfx_motion_blur.tile_size=8", "postfx_motion_blur.samples=7",
                 "postfx_motion_blur.mask_threshold=0.25"});
  expectNoValidationMessages(*dev);
}

}  // namespace
}  // namespace tandem
