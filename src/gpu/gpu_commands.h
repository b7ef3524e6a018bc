// Recording and running GPU work: one command buffer, recorded, submitted and waited for, with
// timestamps around what the caller wants timed (the per-pass rows of `bench`).
#pragma once
#include <volk.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "gpu/gpu_device.h"
#include "gpu/gpu_kernel.h"
#include "gpu/gpu_memory.h"

namespace tandem {

class GpuCommands {
 public:
  // Per recording; checkpoints take two each (a reference render checkpoints every batch, and on
  // a CPU Vulkan every sample).
  static constexpr uint32_t kMaxTimestamps = 1u << 16;
  explicit GpuCommands(GpuDevice& device);
  ~GpuCommands();
  GpuCommands(const GpuCommands&) = delete;
  GpuCommands& operator=(const GpuCommands&) = delete;

  void begin();  // starts a recording (timestamps reset)
  void copy(const GpuBuffer& src, const GpuBuffer& dst, VkDeviceSize bytes,
            VkDeviceSize srcOffset = 0, VkDeviceSize dstOffset = 0);
  // Sets `bytes` (a multiple of 4) of b from `offset` to copies of the 32-bit `value`.
  void fill(const GpuBuffer& b, VkDeviceSize offset, VkDeviceSize bytes, uint32_t value);
  // Runs `kernel` over groups (x, y, z) with `push` (kernel.pushBytes() bytes); `firstY`: the
  // groups' y starts there (gl_WorkGroupID and gl_GlobalInvocationID include it).
  void dispatch(const GpuKernel& kernel, uint32_t x, uint32_t y, uint32_t z, const void* push,
                uint32_t firstY = 0);
  // Submits what was recorded, waits, and records on: timestamps taken before stay valid (the
  // caller may stop between two checkpoints: a long pass on a slow device stays interruptible).
  void checkpoint();
  // Everything recorded before is visible to what is recorded after (compute and copies).
  void barrier();
  // Writes a timestamp once the work before it completes; its index for msBetween.
  uint32_t timestamp();
  void submit();                          // submits what was recorded and waits for it
  void abandon() { recording_ = false; }  // a recording left unsubmitted (an exception)
  // Milliseconds of GPU time between two timestamps of the last submission.
  double msBetween(uint32_t a, uint32_t b) const;
  // The same less the time between checkpoints' submissions: the GPU's working time.
  double activeMs(uint32_t a, uint32_t b) const;
  GpuDevice& device() { return device_; }
  // The command buffer being recorded, for what has no method here (the graphics rasterizer).
  VkCommandBuffer commandBuffer() const { return cb_; }

 private:
  GpuDevice& device_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cb_ = VK_NULL_HANDLE;
  VkQueryPool queries_ = VK_NULL_HANDLE;
  uint32_t used_ = 0;
  bool recording_ = false;
  std::vector<uint64_t> stamps_;
  std::vector<std::pair<uint32_t, uint32_t>> gaps_;  // per checkpoint: its end, the next start
};

}  // namespace tandem
