// One batch of GPU work where the host needs none in between: consecutive GPU passes record into
// one command buffer, submitted before a CPU pass and at the frame's end. Batching changes
// nothing drawn: a batched frame equals, bit for bit, the same frame with every pass submitted on
// its own (FrameContext::isolatePasses flushes after each), its passes keep their timing rows,
// and a frame of GPU passes is one batch.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/interrupt.h"
#include "gpu/gpu_test_util.h"
#include "pipeline/gpu_frame.h"
#include "pipeline/renderer.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {
namespace {

// `batches`: how many a frame should make (1 with every pass on the GPU; one more for each run of
// GPU passes after a CPU pass).
void compareBatching(const std::shared_ptr<GpuDevice>& dev, const std::string& pipeline,
                     const char* sceneName, uint64_t batches, int frames,
                     const std::vector<std::string>& params = {},
                     const std::function<void(Pipeline&)>& edit = {}) {
  const Scene scene = loadScene(sceneName);
  CameraDesc cam = defaultCamera(scene);
  RenderSettings rs{.width = 160, .height = 90, .gpu = dev};
  const auto load = [&] {
    Pipeline p = Pipeline::load(pipeline);
    for (const std::string& q : params) p.setParam(q, "test");
    if (edit) edit(p);
    return p;
  };
  Renderer batched(scene, load(), rs);
  Renderer alone(scene, load(), rs);
  alone.context().isolatePasses = true;
  const std::string what = pipeline + " on " + sceneName;
  const Vec3 step = (cam.lookAt - cam.position) * 0.02f + Vec3(0.05f, 0.0f, 0.0f);
  for (int f = 0; f < frames; ++f) {
    const std::string at = what + ", frame " + std::to_string(f);
    const uint64_t before = batched.context().gpu->batches();
    const FrameTimings ft = batched.renderFrame(f, cam);
    EXPECT_EQ(batched.context().gpu->batches() - before, batches) << at;
    alone.renderFrame(f, cam);
    // Each GPU pass keeps its row (GPU time) and its host row, in the pipeline's order.
    size_t next = 0, onGpu = 0, submits = 0;
    for (const PassTiming& t : ft.passes) {
      EXPECT_TRUE(std::isfinite(t.ms) && t.ms >= 0) << at << ": " << t.name;
      submits += t.name == "gpu_submit" ? 1 : 0;
      if (t.name.ends_with("/host")) ++onGpu;
      if (next < batched.pipeline().passes.size() &&
          t.name == batched.pipeline().passes[next]->name())
        ++next;
    }
    EXPECT_EQ(next, batched.pipeline().passes.size()) << at << ": rows out of order or missing";
    EXPECT_GT(onGpu, 0u) << at;
    EXPECT_EQ(submits, 1u) << at;
    const Buffer &a = batched.output(), &b = alone.output();
    ASSERT_TRUE(a.sameShape(b)) << at;
    size_t differ = 0;
    for (size_t i = 0; i < a.data.size(); ++i) differ += a.data[i] != b.data[i] ? 1 : 0;
    EXPECT_EQ(differ, 0u) << at << ": batching changed the image";
    for (const auto& [name, value] : alone.context().counters)
      EXPECT_EQ(batched.context().counter(name, -1), value) << at << ": counter " << name;
    cam.position = cam.position + step;
  }
}

TEST(GpuBatch, BatchedFramesEqualPassByPassOnes) {
  REQUIRE_GPU(dev);
  compareBatching(dev, "deferred", "spheres", 1, 2);
  compareBatching(dev, "hybrid-heuristic-taa", "spheres", 1, 3);
  compareBatching(dev, "foveated-base", "cornell", 1, 2);
  // The G-buffer, foveation, path tracer, direct light and denoiser on the GPU; a pass only the
  // CPU has; tonemap on the GPU again: two batches.
  compareBatching(dev, "foveated-base", "cornell", 2, 2, {"nh_denoise.color_weight=variance"},
                  [](Pipeline& p) { halveOnTheHostBeforeTonemap(p, "denoised"); });
  expectNoValidationMessages(*dev);
}

// A stop (Ctrl-C) inside a batch: on a CPU Vulkan, long dispatches run in bands with a poll
// between them; here the second poll of a frame (the first band's end) throws.
struct Stopped {};
int pollsLeft = 0;
void stopAtSecondPoll() {
  if (pollsLeft-- == 0) throw Stopped{};
}

// The stopped frame's batch is dropped with everything on the device (shadow maps, probes and
// copies it was to write): the next frame renders whole, equal bit for bit to one never stopped.
TEST(GpuBatch, AFrameAfterAStoppedBatchRendersWhole) {
  REQUIRE_GPU(dev);
  if (dev->info().hardware) GTEST_SKIP() << "a GPU dispatches whole: no poll inside a batch";
  const Scene scene = loadScene("spheres");
  const CameraDesc cam = defaultCamera(scene);
  RenderSettings rs{.width = 160, .height = 90, .gpu = dev};
  Renderer stopped(scene, Pipeline::load("hybrid-heuristic"), rs);
  Renderer whole(scene, Pipeline::load("hybrid-heuristic"), rs);
  stopped.renderFrame(0, cam);
  whole.renderFrame(0, cam);
  {
    pollsLeft = 1;
    InterruptPoll poll(stopAtSecondPoll);
    EXPECT_THROW(stopped.renderFrame(1, cam), Stopped);
  }
  EXPECT_FALSE(stopped.context().gpu->isOpen());
  stopped.renderFrame(1, cam);
  whole.renderFrame(1, cam);
  const Buffer &a = stopped.output(), &b = whole.output();
  ASSERT_TRUE(a.sameShape(b));
  size_t differ = 0;
  for (size_t i = 0; i < a.data.size(); ++i) differ += a.data[i] != b.data[i] ? 1 : 0;
  EXPECT_EQ(differ, 0u);
  expectNoValidationMessages(*dev);
}

}  // namespace
}  // namespace tandem
