// Device memory: buffers sub-allocated from a few large allocations (Vulkan implementations
// limit how many allocations a process may hold, and each costs a driver call), every buffer
// reachable by its device address (kernels take addresses in push constants: no descriptor sets,
// and no 128 MiB storage-buffer binding limit).
#pragma once
#include <volk.h>

#include <cstdint>
#include <vector>

#include "gpu/gpu_device.h"

namespace tandem {

struct GpuBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceAddress address = 0;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // host-visible buffers only
  int block = -1;          // where it was sub-allocated (-1: not allocated)
  VkDeviceSize offset = 0;
  explicit operator bool() const { return buffer != VK_NULL_HANDLE; }
};

class GpuMemory {
 public:
  // Allocations are at least this large (one buffer larger than it gets an allocation its size).
  static constexpr VkDeviceSize kBlockBytes = VkDeviceSize(64) << 20;
  explicit GpuMemory(GpuDevice& device) : device_(device) {}
  ~GpuMemory();
  GpuMemory(const GpuMemory&) = delete;
  GpuMemory& operator=(const GpuMemory&) = delete;

  // A storage buffer of `bytes` (> 0) that copies can read and write: device-local, or
  // host-visible and mapped (staging) when `hostVisible`. Out of device memory is a GpuError
  // naming the size.
  GpuBuffer allocate(VkDeviceSize bytes, bool hostVisible);
  // Gives b's range back to its allocation (b becomes empty).
  void release(GpuBuffer& b);
  VkDeviceSize allocatedBytes() const;  // the large allocations together

 private:
  struct Block {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    uint32_t type = 0;
    VkDeviceSize size = 0;
    void* mapped = nullptr;
    std::vector<std::pair<VkDeviceSize, VkDeviceSize>> free;  // offset, size; sorted
  };
  uint32_t memoryType(uint32_t allowed, bool hostVisible) const;
  bool carve(Block& b, VkDeviceSize size, VkDeviceSize align, VkDeviceSize* offset);
  GpuDevice& device_;
  std::vector<Block> blocks_;
};

}  // namespace tandem
