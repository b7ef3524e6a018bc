// A compute kernel: SPIR-V compiled from src/gpu/shaders at build time and embedded, run with its
// arguments (buffer device addresses and values) in push constants, so no descriptor sets.
#pragma once
#include <volk.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "gpu/gpu_device.h"

namespace tandem {

class GpuKernel {
 public:
  // `spirv` of `words` 32-bit words; `pushBytes`: the size of the kernel's push-constant block
  // (at most 128, what every Vulkan device offers).
  GpuKernel(GpuDevice& device, std::string name, const uint32_t* spirv, size_t words,
            uint32_t pushBytes);
  ~GpuKernel();
  GpuKernel(const GpuKernel&) = delete;
  GpuKernel& operator=(const GpuKernel&) = delete;
  VkPipeline pipeline() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }
  uint32_t pushBytes() const { return pushBytes_; }
  const std::string& name() const { return name_; }

 private:
  GpuDevice& device_;
  std::string name_;
  uint32_t pushBytes_;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace tandem
