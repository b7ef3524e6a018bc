// Tan et al. 2022's depth-of-field passes on the GPU against the CPU: dof_coc, postfx_dof (the
// half-resolution gather and its bokeh buffer), rt_dof (the lens rays, with and without
// reuse_raster) and dof_composite, each given the same inputs on both devices (the buffers a CPU
// frame of the pipeline left), in `postfx-dof`, `hybrid-dof` (the composite with rt_recon) and
// `rt-dof` (mode rt), with the polygonal aperture, the median and the silhouette rule switched,
// and a pinhole; and `postfx-dof` on the GPU whole.
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

const std::set<std::string> kDofPasses = {"dof_coc",      "postfx_dof",       "ray_mask",
                                          "rt_dof",       "dof_accumulation", "dof_reconstruction",
                                          "dof_composite"};

Scene dofScene(const char* name) {
  return loadScene(std::string(TANDEM_SOURCE_DIR) + "/scenes/" + name + ".json");
}

// The pipeline's image-space DoF passes (with `params`), alone.
Pipeline dofPasses(const std::string& pipeline, const std::vector<std::string>& params) {
  Pipeline full = Pipeline::load(pipeline);
  for (const std::string& p : params) full.setParam(p, "test");
  Pipeline p;
  p.name = pipeline + " (depth of field)";
  for (auto& pass : full.passes)
    if (kDofPasses.count(pass->type())) {
      p.output = pass->bufferName("dof");
      p.passes.push_back(std::move(pass));
    }
  return p;
}

// A frame of `pipeline` on the CPU; then its DoF passes run again from that frame's buffers, on
// the CPU and on the GPU, and their outputs compared.
void comparePasses(const std::shared_ptr<GpuDevice>& dev, const std::string& pipeline,
                   const Scene& scene, CameraDesc cam, const std::string& what,
                   const std::vector<std::string>& params = {}) {
  RenderSettings rs{.width = 128, .height = 72};
  Renderer cpu(scene, Pipeline::load(pipeline), rs);
  for (int f = 0; f < 2; ++f) {
    cpu.renderFrame(f, cam);
    cam.position = cam.position + Vec3(0.05f, 0.0f, 0.02f);
  }
  FrameContext runs[2];
  for (int onGpu = 0; onGpu < 2; ++onGpu) {
    FrameContext& ctx = runs[onGpu];
    // The same frame again (the gather's ring rotation), last frame's accumulation with it.
    ctx = frameAgain(cpu.context(), onGpu ? dev : nullptr);
    Pipeline p = dofPasses(pipeline, params);
    for (const auto& pass : p.passes)  // what the passes write, written anew
      for (const BufferSlot& o : pass->outputs()) ctx.buffers.erase(pass->bufferName(o.slot));
    const FrameTimings ft = p.execute(ctx);
    size_t hosts = 0;
    for (const PassTiming& t : ft.passes) hosts += t.name.ends_with("/host") ? 1 : 0;
    EXPECT_EQ(hosts, onGpu ? p.passes.size() : 0u) << what << ": a pass did not run on the GPU";
  }
  const std::string at = pipeline + ", " + what;
  // The lens rays: the same rays on both devices, but where one passes within rounding of two
  // surfaces Embree and the GPU's traversal may each take another (a few pixels).
  // The ray mask: eq. 4 rounds, so a value within rounding of a half may give one ray more.
  for (const char* name : {"ray_mask", "rt_near", "rt_far", "rt_hit", "rt_far_position"}) {
    if (!runs[0].buffers.count(name)) continue;
    const Buffer &c = runs[0].input(name), &g = runs[1].input(name);
    ASSERT_TRUE(c.sameShape(g)) << at << ": " << name;
    for (float v : g.data) ASSERT_TRUE(std::isfinite(v)) << at << ": " << name;
    const double same = agreement(c, g, 1e-3f);
    EXPECT_GE(same, 0.995) << at << ": " << name;
    std::printf("%s: %s %.2f %% of the pixels agree\n", at.c_str(), name, 100.0 * same);
  }
  for (const char* q : {"rt_dof/lens_rays", "rt_dof/reused_share", "rt_dof/shadow_traced",
                        "dof_accumulation/mean_variance", "dof_accumulation/variance_above_1e-6",
                        "ray_mask/rays_per_pixel", "ray_mask/masked_share"}) {
    const double cpuValue = runs[0].counter(q, -1), gpuValue = runs[1].counter(q, -2);
    if (cpuValue == -1) continue;  // not reported (no rays; ray_mask's mode all)
    EXPECT_NEAR(gpuValue, cpuValue, 0.01 * std::abs(cpuValue) + 1e-3) << at << ": " << q;
  }
  for (const char* name : {"coc", "postfx", "bokeh", "acc_near", "acc_far", "acc_moments",
                           "rt_color", "dof_variance", "rt_recon", "dof"}) {
    if (!runs[0].buffers.count(name)) continue;
    const Buffer &c = runs[0].input(name), &g = runs[1].input(name);
    ASSERT_TRUE(c.sameShape(g)) << at << ": " << name;
    for (float v : g.data) ASSERT_TRUE(std::isfinite(v)) << at << ": " << name;
    if (std::string(name) == "coc") {  // pixels, signed: relative
      EXPECT_GE(agreement(c, g, 1e-5f), 1.0) << at << ": coc";
      continue;
    }
    // The bar of a deterministic GPU pass, and all but 0.1 % of the pixels within 1e-3 (the
    // devices round alike but for a few ulps: on lavapipe the image-space passes agree bit for
    // bit); 1 % downstream of lens rays, where a ray's near-tie spreads through the
    // accumulation's reprojection and the reconstruction's gather.
    const bool afterRays = runs[0].buffers.count("rt_near") && std::string(name) != "postfx" &&
                           std::string(name) != "bokeh";
    const double db = psnr(c, g, 1.0);
    EXPECT_GE(db, 45.0) << at << ": " << name;
    EXPECT_GE(agreement(c, g, 1e-3f), afterRays ? 0.99 : 0.999) << at << ": " << name;
    testing::Test::RecordProperty(at + ": " + name + " dB", std::to_string(db));
    std::printf("%s: %s %.1f dB\n", at.c_str(), name, db);
  }
}

TEST(GpuDof, PassesMatchTheCpuOnTheSameInputs) {
  REQUIRE_GPU(dev);
  for (const char* name : {"dof_fg", "dof_bg"}) {
    const Scene scene = dofScene(name);
    comparePasses(dev, "postfx-dof", scene, defaultCamera(scene), name);
  }
  const Scene fg = dofScene("dof_fg");
  const CameraDesc cam = defaultCamera(fg);
  comparePasses(dev, "postfx-dof", fg, cam, "disk aperture, no median",
                {"postfx_dof.polygon=false", "postfx_dof.median=false"});
  comparePasses(
      dev, "postfx-dof", fg, cam, "eq. 7 silhouettes, no bokeh, no fine gather",
      {"dof_composite.silhouette=eq7", "dof_composite.bokeh=false", "dof_composite.fine_coc=0"});
  comparePasses(dev, "hybrid-dof", fg, cam, "with rt_recon, reuse_raster");
  comparePasses(dev, "hybrid-dof", fg, cam, "shading every lens ray",
                {"rt_dof.reuse_raster=false"});
  comparePasses(dev, "rt-dof", fg, cam, "mode rt, 2 rays a pixel", {"ray_mask.m=2"});
  comparePasses(dev, "hybrid-dof", fg, cam, "the near field dilated", {"ray_mask.dilate=true"});
  CameraDesc pinhole = cam;
  pinhole.apertureDiameter = 0;
  comparePasses(dev, "postfx-dof", fg, pinhole, "a pinhole");
  expectNoValidationMessages(*dev);
}

// Every depth-of-field pipeline runs on the GPU whole, and over three frames of a moving camera
// (the TAA and the ray-traced DoF's accumulation keeping their history there) gives the CPU's
// image: PSNR >= 45 dB where both saw the same surface.
void compareWhole(const std::shared_ptr<GpuDevice>& dev, const std::string& pipeline,
                  const std::vector<std::string>& params = {}) {
  const Scene scene = dofScene("dof_fg");
  CameraDesc cam = defaultCamera(scene);
  RenderSettings rs{.width = 160, .height = 90};
  const auto load = [&] {
    Pipeline p = Pipeline::load(pipeline);
    for (const std::string& q : params) p.setParam(q, "test");
    return p;
  };
  Renderer cpu(scene, load(), rs);
  rs.gpu = dev;
  Renderer gpu(scene, load(), rs);
  for (int f = 0; f < 3; ++f) {
    const std::string at = pipeline + ", frame " + std::to_string(f);
    cpu.renderFrame(f, cam);
    const FrameTimings ft = gpu.renderFrame(f, cam);
    size_t hosts = 0;
    for (const PassTiming& t : ft.passes) hosts += t.name.ends_with("/host") ? 1 : 0;
    EXPECT_EQ(hosts, gpu.pipeline().passes.size()) << at << ": a pass ran on the CPU";
    const FrameContext &c = cpu.context(), &g = gpu.context();
    expectAgreement(
        imageAgreement(cpu.output(), gpu.output(), c.input("object_id"), g.input("object_id")), at);
    cam.position = cam.position + Vec3(0.05f, 0.0f, 0.02f);
  }
}

TEST(GpuDof, PipelinesRunOnTheGpuWhole) {
  REQUIRE_GPU(dev);
  compareWhole(dev, "postfx-dof");
  compareWhole(dev, "hybrid-dof");
  compareWhole(dev, "rt-dof", {"ray_mask.m=2"});
  expectNoValidationMessages(*dev);
}

}  // namespace
}  // namespace tandem
