// Walewski et al. 2019's hybrid with its passes on the GPU against the CPU: rt_secondary's
// shadow, reflection and refraction buffers and traced mask, and the composited image, of
// `hybrid-all` (every reflective and transparent object traced; shadows classified by the shadow
// maps, traced, or looked up in the maps) on the built-in scenes and the feature scene, over three
// frames of a moving camera; classified shadows on the GPU against its shadow rays; and the
// heuristic's partial objects, mask for mask.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <cmath>

#include "gpu/feature_scene.h"
#include "gpu/gpu_test_util.h"
#include "pipeline/renderer.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {
namespace {

// expectAgreement, where secondary rays may also tie: a reflected ray that grazes a silhouette
// within rounding takes another surface on one device (the primary object ids cannot tell). Such
// a buffer passes when all but 0.05 % of its pixels agree to 1e-3 (a few pixels at 160x90).
void expectSecondaryAgreement(const Buffer& cpu, const Buffer& gpu, const Buffer& cpuIds,
                              const Buffer& gpuIds, const std::string& what) {
  const ImageAgreement a = imageAgreement(cpu, gpu, cpuIds, gpuIds);
  if (a.psnr < 45.0 && agreement(cpu, gpu, 1e-3f) >= 0.9995) {
    EXPECT_LE(a.ties, 0.002) << what;
    EXPECT_EQ(a.tiesOffEdges, 0) << what;
    return;
  }
  expectAgreement(a, what);
}

// `shadows`: rt_secondary's shadow mode (classified, rays, maps); `params`: more settings.
void compareHybrid(const std::shared_ptr<GpuDevice>& dev, const std::string& pipeline,
                   const Scene& scene, CameraDesc cam, const std::string& what,
                   const std::string& shadows = "classified",
                   const std::vector<std::string>& params = {}, int frames = 3) {
  RenderSettings rs{.width = 160, .height = 90};
  const auto load = [&] {
    Pipeline p = Pipeline::load(pipeline);
    p.setParam("rt_secondary.shadows=" + shadows, "test");
    for (const std::string& q : params) p.setParam(q, "test");
    return p;
  };
  Renderer cpu(scene, load(), rs);
  rs.gpu = dev;
  Renderer gpu(scene, load(), rs);
  const Vec3 step = (cam.lookAt - cam.position) * 0.02f + Vec3(0.05f, 0.0f, 0.0f);
  for (int f = 0; f < frames; ++f) {
    cpu.renderFrame(f, cam);
    const FrameTimings ft = gpu.renderFrame(f, cam);
    // A GPU pass has a row of its host time; every pass of these pipelines has a GPU version.
    int onGpu = 0, passes = 0;
    for (const PassTiming& t : ft.passes) onGpu += t.name.ends_with("/host") ? 1 : 0;
    for (const PassTiming& t : ft.passes)
      passes += t.name.find(':') == std::string::npos && t.name.find('/') == std::string::npos &&
                        t.name != "frame" && t.name != "history" && t.name != "scene_update" &&
                        t.name != "gpu_submit"
                    ? 1
                    : 0;
    EXPECT_EQ(onGpu, passes) << what << ": a pass ran on the CPU";
    const std::string at =
        pipeline + ", " + what + ", shadows " + shadows + ", frame " + std::to_string(f);
    const FrameContext &c = cpu.context(), &g = gpu.context();
    const Buffer &cIds = c.input("object_id"), &gIds = g.input("object_id");
    for (const char* name : {"shadow", "reflection", "refraction", "traced_mask", "composite"})
      if (c.buffers.count(name))
        expectSecondaryAgreement(c.input(name), g.input(name), cIds, gIds, at + ": " + name);
    // Maps only for the lights in view: the device finds them over smaller tiles than the CPU,
    // so never more of them.
    if (shadows != "rays") {
      const double mapped = g.counter("shadow_maps/mapped_lights", -1);
      EXPECT_GT(mapped, 0) << at;
      EXPECT_LE(mapped, c.counter("shadow_maps/mapped_lights", -1)) << at;
    }
    if (c.buffers.count("fallback")) {
      const Buffer &cf = c.input("fallback"), &gf = g.input("fallback");
      expectSecondaryAgreement(cf, gf, cIds, gIds, at + ": fallback");
      double covered = 0;  // pixels the fallback stood in for: effects, shadows
      for (size_t i = 0; i < cf.pixelCount(); ++i)
        covered += cf.data[i * size_t(cf.channels) + 9] + cf.data[i * size_t(cf.channels) + 10];
      EXPECT_GT(covered, 0) << at << ": the fallback covered nothing";
      EXPECT_EQ(c.counter("ss_fallback/probes_drawn", 0), g.counter("ss_fallback/probes_drawn", 0))
          << at;
    }
    expectSecondaryAgreement(cpu.output(), gpu.output(), cIds, gIds, at + ": output");
    // The same work: each share of the light-surface pairs (traced, and decided by the maps)
    // within 1 % (near-ties of which light a pixel asks about, or of a texel's depth test).
    for (const char* q : {"shadow_traced", "shadow_lit", "shadow_shadowed"}) {
      const std::string name = std::string("rt_secondary/") + q;
      const double cpuShare = c.counter(name, -1), gpuShare = g.counter(name, -2);
      EXPECT_NEAR(gpuShare, cpuShare, 0.01 * cpuShare + 1e-3) << at << ": " << q;
    }
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
  const Scene atrium = loadScene("atrium");
  compareHybrid(dev, "hybrid-all", atrium, defaultCamera(atrium), "atrium", "rays");
  compareHybrid(dev, "hybrid-all", atrium, defaultCamera(atrium), "atrium", "maps");
  expectNoValidationMessages(*dev);
}

// TAA over 8 frames of a moving camera after the hybrid, all on the GPU (its history kept there).
TEST(GpuHybrid, HeuristicHybridWithTaaMatchesTheCpuOverEightFrames) {
  REQUIRE_GPU(dev);
  const Scene spheres = loadScene("spheres");
  compareHybrid(dev, "hybrid-heuristic-taa", spheres, defaultCamera(spheres), "spheres",
                "classified", {"heuristic.budget=20000"}, 8);
  expectNoValidationMessages(*dev);
}

// hybrid-budget's budget is calibrated from the device's own ray-tracing time, so its selection
// is the device's: it runs there whole and gives a finite image, not the CPU's.
TEST(GpuHybrid, BudgetHybridRunsOnTheGpuWhole) {
  REQUIRE_GPU(dev);
  const Scene spheres = loadScene("spheres");
  RenderSettings rs{.width = 160, .height = 90, .gpu = dev};
  Renderer r(spheres, Pipeline::load("hybrid-budget"), rs);
  for (int f = 0; f < 3; ++f) {
    const FrameTimings ft = r.renderFrame(f, defaultCamera(spheres));
    int hosts = 0;
    for (const PassTiming& t : ft.passes) hosts += t.name.ends_with("/host") ? 1 : 0;
    EXPECT_EQ(hosts, 7) << "frame " << f << ": every one of its 7 passes on the GPU";
  }
  for (float v : r.output().data) ASSERT_TRUE(std::isfinite(v));
  expectNoValidationMessages(*dev);
}

// The check of classified shadows: on the GPU they give the image its shadow rays give
// (the maps decide only where they are certain), while deciding a share of the pairs.
TEST(GpuHybrid, ClassifiedShadowsEqualShadowRays) {
  REQUIRE_GPU(dev);
  for (const char* name : {"cornell", "atrium"}) {
    const Scene scene = loadScene(name);
    RenderSettings rs{.width = 160, .height = 90, .gpu = dev};
    Pipeline classified = Pipeline::load("hybrid-all"), rays = Pipeline::load("hybrid-all");
    classified.setParam("rt_secondary.shadows=classified", "test");
    rays.setParam("rt_secondary.shadows=rays", "test");
    Renderer c(scene, std::move(classified), rs), r(scene, std::move(rays), rs);
    c.renderFrame(0, defaultCamera(scene));
    r.renderFrame(0, defaultCamera(scene));
    const FrameContext &cc = c.context(), &rc = r.context();
    EXPECT_GE(psnr(cc.input("shadow"), rc.input("shadow"), 1.0), 45.0) << name;
    EXPECT_GE(psnr(c.output(), r.output(), 1.0), 45.0) << name;
    const double decided =
        cc.counter("rt_secondary/shadow_lit", 0) + cc.counter("rt_secondary/shadow_shadowed", 0);
    EXPECT_GT(decided, 0.05) << name << ": the maps decided almost nothing";
    EXPECT_LT(cc.counter("rt_secondary/shadow_traced", 1),
              rc.counter("rt_secondary/shadow_traced", 0))
        << name;
  }
  expectNoValidationMessages(*dev);
}

// The heuristic's selection with ss_fallback standing in for what it leaves out (a budget small
// enough that it does): reflection probes, the screen-space march and the sky for reflections
// and refractions, shadow maps for shadows.
TEST(GpuHybrid, HeuristicHybridMatchesTheCpu) {
  REQUIRE_GPU(dev);
  const Scene spheres = loadScene("spheres");
  const std::string small = "heuristic.budget=20000";
  for (const char* mode : {"probe", "screen_space", "environment"})
    compareHybrid(dev, "hybrid-heuristic", spheres, defaultCamera(spheres),
                  std::string("spheres, fallback ") + mode, "classified",
                  {small, std::string("ss_fallback.mode=") + mode});
  compareHybrid(dev, "hybrid-heuristic", featureScene(), featureCamera(), "features", "classified",
                {small});
  // The map shadows in ss_fallback and blend instead of in deferred shading.
  compareHybrid(dev, "hybrid-heuristic", featureScene(), featureCamera(),
                "features, fallback shadows", "classified",
                {small, "deferred_shading.shadows=off", "ss_fallback.shadows=shadow_map"});
  expectNoValidationMessages(*dev);
}

// The heuristic alone, run again from `from`'s object ids with `params` (a fresh pass, its costs
// priced by the prior), on the GPU with `dev` (null: the CPU).
FrameContext heuristicAgain(const FrameContext& from, const std::vector<std::string>& params,
                            const std::shared_ptr<GpuDevice>& dev) {
  Pipeline full = Pipeline::load("hybrid-budget");
  full.setParam("heuristic.deadline=false", "test");  // the budget as given, not overcommitted
  for (const std::string& q : params) full.setParam(q, "test");
  Pipeline p;
  p.name = "heuristic";
  for (auto& pass : full.passes)
    if (pass->type() == "heuristic") {
      p.output = pass->bufferName("heuristic_mask");
      p.passes.push_back(std::move(pass));
    }
  FrameContext ctx = frameAgain(from, dev);
  ctx.history.clear();  // no ray-tracing times: every node priced by the prior, on any machine
  for (const BufferSlot& o : p.passes.front()->outputs())
    ctx.buffers.erase(p.passes.front()->bufferName(o.slot));
  const FrameTimings ft = p.execute(ctx);
  int hosts = 0;
  for (const PassTiming& t : ft.passes) hosts += t.name.ends_with("/host") ? 1 : 0;
  EXPECT_EQ(hosts, dev ? 1 : 0) << "the heuristic did not run on the GPU";
  return ctx;
}

// partial_objects with a ms budget: what the budget leaves buys the central part of the most
// relevant node left out. From the same ids both devices select the same nodes and the
// same part, pixel for pixel (the distances to each view's centre are binned and compared
// exactly), mono and stereo (each eye's own centre), at budgets from a tenth to nine tenths of
// everything visible (where what is left pays for a pixel of the part or more in some of them).
TEST(GpuHybrid, PartialObjectsAreTheCpusPixels) {
  REQUIRE_GPU(dev);
  const Scene spheres = loadScene("spheres");
  const CameraDesc cam = defaultCamera(spheres);
  // The budget's prior before any frame calibrated it: units of predicted CPU ms per wall ms.
  const double prior = double(tbb::this_task_arena::max_concurrency());
  for (bool stereo : {false, true}) {
    RenderSettings rs{.width = 160, .height = 90};
    rs.stereo.enabled = stereo;
    Renderer cpu(spheres, Pipeline::load("hybrid-budget"), rs);
    cpu.renderFrame(0, cam);
    const FrameContext& from = cpu.context();
    const double everything = heuristicAgain(from, {"heuristic.budget_ms=1e6"}, nullptr)
                                  .counter("heuristic/selected_cost");
    ASSERT_GT(everything, 0);
    int parts = 0;  // budgets where the part added pixels
    for (int tenths = 1; tenths <= 9; ++tenths) {
      const std::string at = std::string(stereo ? "stereo" : "mono") + ", budget " +
                             std::to_string(tenths) + " tenths of everything";
      const std::string budget =
          "heuristic.budget_ms=" + std::to_string(0.1 * tenths * everything / prior);
      const std::vector<std::string> params = {"heuristic.partial_objects=true", budget};
      const FrameContext c = heuristicAgain(from, params, nullptr);
      const FrameContext g = heuristicAgain(from, params, dev);
      const double fraction = c.counter("heuristic/partial_fraction");
      EXPECT_EQ(g.counter("heuristic/partial_fraction", -1), fraction) << at;
      EXPECT_EQ(g.counter("heuristic/selected", -1), c.counter("heuristic/selected")) << at;
      EXPECT_EQ(g.input("heuristic_order").data, c.input("heuristic_order").data) << at;
      const Buffer &cm = c.input("heuristic_mask"), &gm = g.input("heuristic_mask");
      ASSERT_TRUE(cm.sameShape(gm)) << at;
      size_t differ = 0;
      for (size_t i = 0; i < cm.data.size(); ++i) differ += cm.data[i] != gm.data[i] ? 1 : 0;
      EXPECT_EQ(differ, 0u) << at << ": mask values that differ";
      // The part's pixels: the mask less the one without partial objects.
      const FrameContext whole = heuristicAgain(from, {budget}, nullptr);
      const Buffer& wm = whole.input("heuristic_mask");
      size_t added = 0, lost = 0;
      for (size_t i = 0; i < cm.data.size(); ++i) {
        added += cm.data[i] > wm.data[i] ? 1 : 0;
        lost += cm.data[i] < wm.data[i] ? 1 : 0;
      }
      EXPECT_EQ(lost, 0u) << at;
      if (fraction == 0) {
        EXPECT_EQ(added, 0u) << at;
      }
      parts += added > 0 ? 1 : 0;
      std::printf("%s: part %.4f of a node, %zu mask values added\n", at.c_str(), fraction, added);
    }
    EXPECT_GE(parts, 2) << (stereo ? "stereo" : "mono") << ": no budget left a part to trace";
  }
  expectNoValidationMessages(*dev);
}

}  // namespace
}  // namespace tandem
