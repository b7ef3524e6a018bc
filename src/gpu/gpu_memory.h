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

// What a buffer is for, which picks its memory type. Device: kernels alone (device-local).
// Upload: the host writes, the device reads (host-visible and coherent: write-combined where the
// driver offers it, fine for sequential writes). Readback: the device writes, the host reads
// (host-visible, and cached where a type is: reads of uncached memory are many times slower).
enum class MemoryUse { Device, Upload, Readback };

class GpuMemory {
 public:
  // Allocations are at least this large (one buffer larger than it gets an allocation its size).
  static constexpr VkDeviceSize kBlockBytes = VkDeviceSize(64) << 20;
  explicit GpuMemory(GpuDevice& device) : device_(device) {}
  ~GpuMemory();
  GpuMemory(const GpuMemory&) = delete;
  GpuMemory& operator=(const GpuMemory&) = delete;

  // A storage buffer of `bytes` (> 0) that copies can read and write, in memory for `use`
  // (mapped unless Device). Out of device memory is a GpuError naming the size.
  GpuBuffer allocate(VkDeviceSize bytes, MemoryUse use);
  // The property flags of the memory `b` lives in.
  VkMemoryPropertyFlags properties(const GpuBuffer& b) const;
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
  uint32_t memoryType(uint32_t allowed, MemoryUse use) const;
  bool carve(Block& b, VkDeviceSize size, VkDeviceSize align, VkDeviceSize* offset);
  GpuDevice& device_;
  std::vector<Block> blocks_;
};

}  // namespace tandem
