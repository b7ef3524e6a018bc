#include "gpu/gpu_kernel.h"

namespace tandem {

GpuKernel::GpuKernel(GpuDevice& device, std::string name, const uint32_t* spirv, size_t words,
                     uint32_t pushBytes)
    : device_(device), name_(std::move(name)), pushBytes_(pushBytes) {
  if (pushBytes > 128) throw GpuError("GPU: kernel " + name_ + ": push constants over 128 bytes");
  VkDevice dev = device.device();
  VkShaderModuleCreateInfo si{};
  si.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  si.codeSize = words * 4;
  si.pCode = spirv;
  VkShaderModule module = VK_NULL_HANDLE;
  checkVk(vkCreateShaderModule(dev, &si, nullptr, &module), "vkCreateShaderModule");
  VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes};
  VkPipelineLayoutCreateInfo li{};
  li.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  li.pushConstantRangeCount = pushBytes ? 1 : 0;
  li.pPushConstantRanges = &range;
  VkResult r = vkCreatePipelineLayout(dev, &li, nullptr, &layout_);
  if (r == VK_SUCCESS) {
    VkComputePipelineCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    ci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = module;
    ci.stage.pName = "main";
    ci.layout = layout_;
    ci.flags = VK_PIPELINE_CREATE_DISPATCH_BASE_BIT;  // banded dispatches (GpuCommands::dispatch)
    r = vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline_);
  }
  vkDestroyShaderModule(dev, module, nullptr);
  if (r != VK_SUCCESS) {
    if (layout_) vkDestroyPipelineLayout(dev, layout_, nullptr);
    checkVk(r, ("creating kernel " + name_).c_str());
  }
}

GpuKernel::~GpuKernel() {
  vkDestroyPipeline(device_.device(), pipeline_, nullptr);
  vkDestroyPipelineLayout(device_.device(), layout_, nullptr);
}

}  // namespace tandem
