// What the GPU tests share: the device they run on (what `--device gpu` would take, with the
// Vulkan validation layers on) or a skip saying why there is none.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>

#include "core/buffer.h"
#include "core/error.h"
#include "eval/metrics/metrics.h"
#include "gpu/gpu_device.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"
#include "pipeline/pipeline.h"

namespace tandem {

// The device the tests run on, or null with the reason in `why`.
inline std::shared_ptr<GpuDevice> testDevice(std::string* why) {
  setenv("TANDEM_VK_VALIDATION", "1", 0);  // before the first instance
  try {
    return GpuDevice::forChoice(DeviceChoice::Gpu, "test");
  } catch (const InputError& e) {
    *why = e.what();
    return nullptr;
  }
}

#define REQUIRE_GPU(dev)                                                                       \
  std::string why;                                                                             \
  std::shared_ptr<GpuDevice> dev = testDevice(&why);                                           \
  if (!dev) GTEST_SKIP() << "no Vulkan device: " << why;                                       \
  ASSERT_TRUE(dev->validating()) << "the Vulkan validation layers are not installed (package " \
                                    "vulkan-validationlayers): GPU tests run only with them";

// A GPU image against the CPU's where both trace the same rays: where a ray passes within
// rounding of two surfaces (a corner where two walls meet, a grazed silhouette) Embree and the
// GPU's traversal may each take another one, so those pixels are told apart by the object ids the
// two sides saw. `psnr` over the pixels where they saw the same object, `ties` the share of the
// others, and `tiesOffEdges` those of them whose 3x3 neighbourhood in the CPU's ids shows no
// pixel of the GPU's object (a disagreement that is not a near-tie: a bug). Given both depth
// buffers, a pixel where both saw their objects at the same depth (coplanar surfaces that
// overlap: an exact tie) is a near-tie too.
struct ImageAgreement {
  double psnrAll = 0, psnr = 0, ties = 0;
  int tiesOffEdges = 0;
};
inline ImageAgreement imageAgreement(const Buffer& cpu, const Buffer& gpu, const Buffer& cpuIds,
                                     const Buffer& gpuIds, const Buffer* cpuDepth = nullptr,
                                     const Buffer* gpuDepth = nullptr) {
  ImageAgreement r;
  r.psnrAll = psnr(cpu, gpu, 1.0);
  Buffer a = cpu, b = gpu;
  size_t ties = 0;
  const int w = cpuIds.width, h = cpuIds.height;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * size_t(w) + size_t(x);
      const float g = gpuIds.data[i];
      if (cpuIds.data[i] == g) continue;
      ++ties;
      for (int k = 0; k < cpu.channels; ++k)
        b.data[i * size_t(cpu.channels) + size_t(k)] = a.data[i * size_t(cpu.channels) + size_t(k)];
      bool near = cpuDepth && gpuDepth && cpuDepth->data[i] > 0 &&
                  std::abs(cpuDepth->data[i] - gpuDepth->data[i]) <= 1e-6f * cpuDepth->data[i];
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx >= 0 && ny >= 0 && nx < w && ny < h)
            near |= cpuIds.data[size_t(ny) * size_t(w) + size_t(nx)] == g;
        }
      r.tiesOffEdges += near ? 0 : 1;
    }
  r.psnr = psnr(a, b, 1.0);
  r.ties = double(ties) / double(std::max<size_t>(cpuIds.data.size(), 1));
  return r;
}
// The share of pixels whose every channel agrees within `tol` (relative to max(1, |value|)).
inline double agreement(const Buffer& a, const Buffer& b, float tol) {
  const size_t pixels = a.pixelCount(), ch = size_t(a.channels);
  size_t same = 0;
  for (size_t i = 0; i < pixels; ++i) {
    bool ok = true;
    for (size_t k = 0; k < ch; ++k) {
      const float x = a.data[i * ch + k], y = b.data[i * ch + k];
      ok &= std::abs(x - y) <= tol * std::max(1.0f, std::abs(x));
    }
    same += ok;
  }
  return double(same) / double(std::max<size_t>(pixels, 1));
}

// The bar of every deterministic GPU pass: PSNR >= 45 dB where both saw the same surface, near
// ties on at most 0.2 % of the pixels, and every one of them on an edge.
inline void expectAgreement(const ImageAgreement& a, const std::string& what) {
  EXPECT_GE(a.psnr, 45.0) << what << " (whole image: " << a.psnrAll << " dB)";
  EXPECT_LE(a.ties, 0.002) << what;
  EXPECT_EQ(a.tiesOffEdges, 0) << what;
}

// A context to run passes again on `from`'s frame: its size, views, scene and seed, the serial
// it had (so they draw the same samples), its buffers and last frame's history; on the GPU `dev`
// (null: the CPU).
inline FrameContext frameAgain(const FrameContext& from, const std::shared_ptr<GpuDevice>& dev) {
  FrameContext ctx;
  ctx.width = from.width;
  ctx.height = from.height;
  ctx.views = from.views;
  ctx.frameIndex = from.frameIndex;
  ctx.serial = from.serial - 1;  // execute() counts it up again
  ctx.buffers = from.buffers;
  ctx.scene = from.scene;
  ctx.frame = from.frame;
  ctx.seed = from.seed;
  ctx.history = from.history;
  ctx.historyReset = false;
  if (dev) ctx.gpu = std::make_shared<GpuFrame>(dev);
  return ctx;
}

inline void expectNoValidationMessages(const GpuDevice& dev) {
  for (const std::string& m : dev.validationMessages()) ADD_FAILURE() << "validation: " << m;
}

// A pass with no GPU version (every built-in pass has one): halves `hdr` into `host_hdr` on the
// CPU, so tests can put a CPU pass between GPU ones.
class HostHalvingPass : public Pass {
 public:
  std::string type() const override { return "host_halving"; }
  std::string description() const override { return "test: a pass only the CPU runs"; }
  std::vector<BufferSlot> inputs() const override { return {{"hdr", 3}}; }
  std::vector<BufferSlot> outputs() const override { return {{"host_hdr", 3}}; }
  void execute(FrameContext& ctx) override {
    const Buffer& in = ctx.input(*this, "hdr");
    Buffer& out = ctx.output(*this, "host_hdr");
    for (size_t i = 0; i < in.data.size(); ++i) out.data[i] = 0.5f * in.data[i];
  }
};

// Puts a HostHalvingPass before the pipeline's last pass (its tonemap), reading `hdr` (the
// buffer the tonemap read), which the tonemap then reads halved.
inline void halveOnTheHostBeforeTonemap(Pipeline& p, const std::string& hdr = "hdr") {
  auto host = std::make_unique<HostHalvingPass>();
  host->bindings["hdr"] = hdr;
  p.passes.insert(p.passes.end() - 1, std::move(host));
  p.passes.back()->bindings["hdr"] = "host_hdr";
  p.validate("test");
}

}  // namespace tandem
