// GPU passes against their CPU passes, on whatever Vulkan device `--device gpu` would take (in
// CI: lavapipe, Mesa's CPU Vulkan), with the Vulkan validation layers on: any message they print
// fails the test. Without a Vulkan device every test here skips, saying so.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>

#include "core/color.h"
#include "eval/metrics/metrics.h"
#include "gpu/gpu_device.h"
#include "gpu/gpu_memory.h"
#include "gpu/gpu_test_util.h"
#include "passes/common/downsample.h"
#include "passes/common/tonemap.h"
#include "pipeline/gpu_frame.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"
#include "test_util.h"

namespace tandem {
namespace {

TEST(GpuDevice, ListsWhatItOpens) {
  REQUIRE_GPU(dev);
  const std::vector<GpuDeviceInfo> all = listGpuDevices();
  bool found = false;
  for (const GpuDeviceInfo& d : all) found |= d.name == dev->info().name && d.usable;
  EXPECT_TRUE(found);
  EXPECT_GE(dev->info().apiVersion, uint32_t(VK_API_VERSION_1_3));
  EXPECT_GT(dev->info().subgroupSize, 0u);
}

TEST(GpuDevice, ChoicesParseAndBadOnesNameTheField) {
  EXPECT_EQ(parseDeviceChoice("auto", "x", "device"), DeviceChoice::Auto);
  EXPECT_EQ(parseDeviceChoice("gpu", "x", "device"), DeviceChoice::Gpu);
  EXPECT_EQ(GpuDevice::forChoice(DeviceChoice::Cpu, "x"), nullptr);
  try {
    parseDeviceChoice("cuda", "command line", "--device");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "command line: --device: expected auto, cpu or gpu, got 'cuda'");
  }
}

// Sub-allocation: buffers share allocations, freed ranges are reused, and a buffer larger than
// the device is a GpuError naming the size, not a crash.
TEST(GpuMemory, SubAllocatesReusesAndRefusesTooMuch) {
  REQUIRE_GPU(dev);
  {
    GpuMemory mem(*dev);
    GpuBuffer a = mem.allocate(1000, MemoryUse::Device), b = mem.allocate(5000, MemoryUse::Device);
    EXPECT_EQ(a.block, b.block);
    EXPECT_NE(a.address, b.address);
    EXPECT_EQ(mem.allocatedBytes(), GpuMemory::kBlockBytes);
    const VkDeviceAddress first = a.address;
    mem.release(a);
    GpuBuffer c = mem.allocate(800, MemoryUse::Device);
    EXPECT_EQ(c.address, first);  // the freed range, first fit
    GpuBuffer s = mem.allocate(64, MemoryUse::Upload);
    EXPECT_NE(s.mapped, nullptr);
    // What the host reads back lives in cached memory where the device has a type of it.
    GpuBuffer r = mem.allocate(64, MemoryUse::Readback);
    EXPECT_NE(r.mapped, nullptr);
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(dev->physical(), &props);
    constexpr VkMemoryPropertyFlags kCachedHost = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                  VK_MEMORY_PROPERTY_HOST_COHERENT_BIT |
                                                  VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
    bool cachedExists = false;
    for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
      cachedExists |= (props.memoryTypes[i].propertyFlags & kCachedHost) == kCachedHost;
    EXPECT_EQ((mem.properties(r) & kCachedHost) == kCachedHost, cachedExists);
    EXPECT_NE(mem.properties(s) & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT, 0u);
    EXPECT_NE(mem.properties(c) & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0u);
    try {
      mem.allocate(VkDeviceSize(1) << 50, MemoryUse::Device);
      FAIL() << "no error";
    } catch (const GpuError& e) {
      EXPECT_NE(std::string(e.what()).find("out of device memory"), std::string::npos) << e.what();
    }
    mem.release(b);
    mem.release(c);
    mem.release(s);
    mem.release(r);
  }
  expectNoValidationMessages(*dev);
}

// The tonemap kernel against tonemapSpan on values across the range, non-finite and negative
// ones included, for every operator and a few exposures. The GPU's exp and log differ from
// Highway's by a few ulps: 2e-6 is 1/2000 of an 8-bit step.
TEST(GpuTonemap, MatchesTheCpuPassValueForValue) {
  REQUIRE_GPU(dev);
  const int w = 64, h = 32;
  Buffer hdr(w, h, 3);
  for (size_t i = 0; i < hdr.data.size(); ++i)
    hdr.data[i] = float(std::pow(10.0, -6.0 + 9.0 * double(i) / double(hdr.data.size())));
  hdr.data[0] = std::numeric_limits<float>::quiet_NaN();
  hdr.data[1] = std::numeric_limits<float>::infinity();
  hdr.data[2] = -1.0f;
  hdr.data[3] = 3e38f;
  for (const char* op : {"clamp", "reinhard", "aces"})
    for (const double ev : {-3.0, 0.0, 2.5}) {
      Buffer outs[2];
      for (int onGpu = 0; onGpu < 2; ++onGpu) {
        Pipeline p;
        p.passes.push_back(std::make_unique<TonemapPass>());
        p.setParam(std::string("tonemap.operator=") + op, "test");
        p.setParam("tonemap.exposure=" + std::to_string(ev), "test");
        FrameContext ctx;
        ctx.width = w;
        ctx.height = h;
        if (onGpu) ctx.gpu = std::make_shared<GpuFrame>(dev);
        ctx.buffers["hdr"] = hdr;
        p.execute(ctx);
        outs[onGpu] = ctx.input("output");
      }
      float worst = 0;
      for (size_t i = 0; i < outs[0].data.size(); ++i)
        worst = std::max(worst, std::abs(outs[0].data[i] - outs[1].data[i]));
      EXPECT_LE(worst, 2e-6f) << op << " at " << ev << " EV";
    }
  expectNoValidationMessages(*dev);
}

// downsample on the GPU: the CPU's half and quarter images, value for value (the same sums in
// the same order), both filters, on odd sizes whose last row and column reduce what is left.
TEST(GpuDownsample, MatchesTheCpuPassValueForValue) {
  REQUIRE_GPU(dev);
  for (const auto& [w, h] : {std::pair{64, 32}, std::pair{37, 23}}) {
    Buffer hdr(w, h, 3);
    for (size_t i = 0; i < hdr.data.size(); ++i)
      hdr.data[i] = float(std::sin(0.37 * double(i)) * 4.0 + 4.5 + 0.01 * double(i % 97));
    for (const char* filter : {"box", "bilinear"}) {
      FrameContext runs[2];
      for (int onGpu = 0; onGpu < 2; ++onGpu) {
        Pipeline p;
        p.passes.push_back(std::make_unique<DownsamplePass>());
        p.setParam(std::string("downsample.filter=") + filter, "test");
        FrameContext& ctx = runs[onGpu];
        ctx.width = w;
        ctx.height = h;
        if (onGpu) ctx.gpu = std::make_shared<GpuFrame>(dev);
        ctx.buffers["hdr"] = hdr;
        const FrameTimings ft = p.execute(ctx);
        size_t hosts = 0;
        for (const PassTiming& t : ft.passes) hosts += t.name.ends_with("/host") ? 1 : 0;
        EXPECT_EQ(hosts, onGpu ? 1u : 0u) << filter << ": the pass did not run on the GPU";
      }
      for (const char* name : {"half", "quarter"}) {
        const Buffer &c = runs[0].input(name), &g = runs[1].input(name);
        ASSERT_TRUE(c.sameShape(g)) << filter << " " << name;
        EXPECT_EQ(c.width, name[0] == 'h' ? (w + 1) / 2 : (w + 3) / 4);
        float worst = 0;
        for (size_t i = 0; i < c.data.size(); ++i)
          worst = std::max(worst, std::abs(c.data[i] - g.data[i]));
        EXPECT_LE(worst, 1e-5f) << filter << " " << name << " at " << w << "x" << h;
      }
    }
  }
  expectNoValidationMessages(*dev);
}

// Whole pipelines on the GPU, and with some passes there, give the CPU's image on the built-in
// scenes (PSNR >= 45 dB, as every deterministic GPU pass must), and each buffer crosses once a
// frame, as its own timing row with its bytes: `deferred` runs there whole (only its output comes
// back); with a pass only the CPU has between its shading and its tonemap, hdr comes down, the
// CPU pass's host_hdr goes up, and the output comes down.
TEST(GpuPipeline, PipelinesMatchTheCpuAndMoveEachBufferOnce) {
  REQUIRE_GPU(dev);
  for (const char* name : {"cornell", "spheres", "atrium"})
    for (const bool mixed : {false, true}) {
      Scene scene = loadScene(name);
      const CameraDesc cam = defaultCamera(scene);
      RenderSettings rs{.width = 160, .height = 90};
      const auto pipeline = [&] {
        Pipeline p = Pipeline::load("deferred");
        if (mixed) halveOnTheHostBeforeTonemap(p);
        return p;
      };
      Renderer cpu(scene, pipeline(), rs);
      rs.gpu = dev;
      Renderer gpu(scene, pipeline(), rs);
      gpu.context().keepAllOutputs = false;  // as render and bench: only the output comes back
      const std::string what =
          std::string(name) + (mixed ? ", deferred with a CPU pass" : ", deferred");
      for (int f = 0; f < 2; ++f) {
        cpu.renderFrame(f, cam);
        const FrameTimings ft = gpu.renderFrame(f, cam);
        EXPECT_GE(psnr(cpu.output(), gpu.output(), 1.0), 45.0) << what;
        int uploads = 0, downloads = 0, moves = 0;
        for (const PassTiming& t : ft.passes) {
          if (t.name == "upload:host_hdr" || t.name == "download:hdr") {
            t.name[0] == 'u' ? ++uploads : ++downloads;
            EXPECT_EQ(t.bytes, 160.0 * 90 * 3 * 4) << what << ": " << t.name;
          }
          if (t.name == "download:output") ++downloads;
          if (t.name.rfind("upload:", 0) == 0 || t.name.rfind("download:", 0) == 0) ++moves;
        }
        EXPECT_EQ(uploads, mixed ? 1 : 0) << what;
        EXPECT_EQ(downloads, mixed ? 2 : 1) << what;
        EXPECT_EQ(moves, mixed ? 3 : 1) << what;
      }
    }
  expectNoValidationMessages(*dev);
}

// A renderer that keeps its buffers on the device (the experiments' timed frames) moves nothing
// back at a frame's end, and what it fetches afterwards is what one that brings everything back
// holds, value for value, over frames of a temporal pipeline (its history untouched by it).
TEST(GpuPipeline, BuffersKeptOnTheDeviceUntilFetched) {
  REQUIRE_GPU(dev);
  Scene scene = loadScene("cornell");
  CameraDesc cam = defaultCamera(scene);
  RenderSettings rs{.width = 96, .height = 54, .gpu = dev};
  Renderer all(scene, Pipeline::load("deferred-taa"), rs),
      kept(scene, Pipeline::load("deferred-taa"), rs);
  kept.keepOnDevice();
  for (int f = 0; f < 3; ++f) {
    cam.position = cam.position + Vec3(0.02f, 0.0f, 0.0f);
    all.renderFrame(f, cam);
    const FrameTimings ft = kept.renderFrame(f, cam);
    for (const PassTiming& t : ft.passes)
      EXPECT_NE(t.name.rfind("download:", 0), 0u) << "frame " << f << ": " << t.name;
    EXPECT_TRUE(kept.context().gpu->deviceNewer(kept.pipeline().output)) << "frame " << f;
    for (const char* name : {"taa", "motion"})
      EXPECT_EQ(kept.fetch(name).data, all.context().input(name).data) << name << ", frame " << f;
    EXPECT_EQ(kept.output().data, all.output().data) << "frame " << f;
    EXPECT_FALSE(kept.context().gpu->deviceNewer(kept.pipeline().output)) << "frame " << f;
  }
  expectNoValidationMessages(*dev);
}

// TAA on the GPU over 8 frames of a moving camera (its history kept from frame to frame, the
// reprojection through motion vectors, the neighbourhood clamp) gives the CPU's frames: PSNR of
// every frame >= 45 dB, and the history stays on the device (no row moves it).
TEST(GpuPipeline, TaaMatchesTheCpuOverEightFrames) {
  REQUIRE_GPU(dev);
  for (const char* name : {"cornell", "spheres"}) {
    Scene scene = loadScene(name);
    CameraDesc cam = defaultCamera(scene);
    RenderSettings rs{.width = 96, .height = 54};
    Renderer cpu(scene, Pipeline::load("deferred-taa"), rs);
    rs.gpu = dev;
    Renderer gpu(scene, Pipeline::load("deferred-taa"), rs);
    for (int f = 0; f < 8; ++f) {
      cam.position = cam.position + Vec3(0.02f, 0.0f, 0.0f);
      cpu.renderFrame(f, cam);
      const FrameTimings ft = gpu.renderFrame(f, cam);
      const double db = psnr(cpu.context().input("taa"), gpu.context().input("taa"), 1.0);
      EXPECT_GE(db, 45.0) << name << " frame " << f;
      if (f == 7) std::printf("%s: frame 8 PSNR %.1f dB\n", name, db);
      for (const PassTiming& t : ft.passes)
        EXPECT_EQ(t.name.find("history:"), std::string::npos) << name << " frame " << f;
    }
  }
  expectNoValidationMessages(*dev);
}

// A CPU pass reading last frame's value of a buffer a GPU pass wrote: the history kept on the
// device comes back to the host (its own row) before the pass runs, and the pass reads exactly
// what the GPU pass wrote last frame.
class LastFrameMean : public Pass {
 public:
  std::string type() const override { return "last_frame_mean"; }
  std::string description() const override { return "the mean of last frame's taa"; }
  std::vector<BufferSlot> inputs() const override {
    BufferSlot h{"taa", 3};
    h.history = true;
    return {h};
  }
  std::vector<BufferSlot> outputs() const override {
    return {{"mean", 1, BufferKind::Color, Extent::any()}};
  }
  void execute(FrameContext& ctx) override {
    const Buffer* h = ctx.previous(*this, "taa");
    double sum = 0;
    if (h)
      for (float v : h->data) sum += v;
    ctx.output(*this, "mean", 1, 1).data[0] = h ? float(sum / double(h->data.size())) : -1.0f;
  }
};

TEST(GpuPipeline, CpuPassReadsHistoryTheDeviceKept) {
  REQUIRE_GPU(dev);
  Scene scene = loadScene("spheres");
  CameraDesc cam = defaultCamera(scene);
  RenderSettings rs{.width = 96, .height = 54, .gpu = dev};
  Pipeline p = Pipeline::load("deferred-taa");
  p.passes.push_back(std::make_unique<LastFrameMean>());
  Renderer r(scene, std::move(p), rs);
  r.context().keepAllOutputs = false;  // taa stays on the device unless a pass reads it
  r.context().wanted.insert("mean");
  Buffer previous;
  for (int f = 0; f < 3; ++f) {
    cam.position = cam.position + Vec3(0.02f, 0.0f, 0.0f);
    const FrameTimings ft = r.renderFrame(f, cam);
    bool moved = false;
    for (const PassTiming& t : ft.passes) moved |= t.name == "download:history:taa";
    EXPECT_EQ(moved, f > 0) << "frame " << f;
    const float mean = r.context().input("mean").data[0];
    if (f == 0) {
      EXPECT_EQ(mean, -1.0f);
    } else {
      double sum = 0;
      for (float v : previous.data) sum += v;
      EXPECT_FLOAT_EQ(mean, float(sum / double(previous.data.size()))) << "frame " << f;
    }
    // This frame's taa, read back for the next frame's check (not by the pipeline).
    GpuFrame& g = *r.context().gpu;
    previous = Buffer(96, 54, 3);
    g.readBack(g.read("taa"), previous.data.size() * sizeof(float), previous.data.data());
  }
  expectNoValidationMessages(*dev);
}

}  // namespace
}  // namespace tandem
