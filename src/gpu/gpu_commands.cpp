#include "gpu/gpu_commands.h"

#include <string>

#include <stdexcept>

namespace tandem {

GpuCommands::GpuCommands(GpuDevice& device) : device_(device) {
  VkDevice dev = device.device();
  VkCommandPoolCreateInfo pi{};
  pi.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pi.queueFamilyIndex = device.queueFamily();
  checkVk(vkCreateCommandPool(dev, &pi, nullptr, &pool_), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo ai{};
  ai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  ai.commandPool = pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkQueryPoolCreateInfo qi{};
  qi.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
  qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
  qi.queryCount = kMaxTimestamps;
  try {
    checkVk(vkAllocateCommandBuffers(dev, &ai, &cb_), "vkAllocateCommandBuffers");
    checkVk(vkCreateQueryPool(dev, &qi, nullptr, &queries_), "vkCreateQueryPool");
  } catch (...) {
    vkDestroyCommandPool(dev, pool_, nullptr);
    throw;
  }
}

GpuCommands::~GpuCommands() {
  vkDestroyQueryPool(device_.device(), queries_, nullptr);
  vkDestroyCommandPool(device_.device(), pool_, nullptr);
}

void GpuCommands::begin() {
  if (recording_) throw std::logic_error("GPU: a recording was begun inside another");
  checkVk(vkResetCommandBuffer(cb_, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  checkVk(vkBeginCommandBuffer(cb_, &bi), "vkBeginCommandBuffer");
  recording_ = true;
  vkCmdResetQueryPool(cb_, queries_, 0, kMaxTimestamps);
  used_ = 0;
  gaps_.clear();
}

void GpuCommands::copy(const GpuBuffer& src, const GpuBuffer& dst, VkDeviceSize bytes,
                       VkDeviceSize srcOffset, VkDeviceSize dstOffset) {
  if (bytes == 0) return;
  VkBufferCopy region{srcOffset, dstOffset, bytes};
  vkCmdCopyBuffer(cb_, src.buffer, dst.buffer, 1, &region);
}

void GpuCommands::dispatch(const GpuKernel& kernel, uint32_t x, uint32_t y, uint32_t z,
                           const void* push, uint32_t firstY) {
  vkCmdBindPipeline(cb_, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.pipeline());
  if (kernel.pushBytes())
    vkCmdPushConstants(cb_, kernel.layout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, kernel.pushBytes(),
                       push);
  if (firstY)
    vkCmdDispatchBase(cb_, 0, firstY, 0, x, y, z);
  else
    vkCmdDispatch(cb_, x, y, z);
}

void GpuCommands::fill(const GpuBuffer& b, VkDeviceSize offset, VkDeviceSize bytes,
                       uint32_t value) {
  vkCmdFillBuffer(cb_, b.buffer, offset, bytes, value);
}

void GpuCommands::checkpoint() {
  const uint32_t end = timestamp();
  submit();
  // Recording again, the timestamps so far kept (no reset): the time between the two
  // submissions is left out of activeMs.
  checkVk(vkResetCommandBuffer(cb_, 0), "vkResetCommandBuffer");
  auto bi = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  checkVk(vkBeginCommandBuffer(cb_, &bi), "vkBeginCommandBuffer");
  recording_ = true;
  gaps_.push_back({end, timestamp()});
}

void GpuCommands::barrier() {
  VkMemoryBarrier2 mb{};
  mb.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2;
  // Transfers: copies and fills.
  mb.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT;
  mb.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;
  mb.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT;
  mb.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                     VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;
  VkDependencyInfo di{};
  di.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
  di.memoryBarrierCount = 1;
  di.pMemoryBarriers = &mb;
  vkCmdPipelineBarrier2(cb_, &di);
}

uint32_t GpuCommands::timestamp() {
  if (used_ >= kMaxTimestamps)
    throw GpuError("GPU: more than " + std::to_string(kMaxTimestamps) +
                   " timestamps in one recording");
  vkCmdWriteTimestamp2(cb_, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries_, used_);
  return used_++;
}

void GpuCommands::submit() {
  recording_ = false;
  // What the work wrote is visible to the host once the wait returns (staging reads).
  auto mb = vkStruct<VkMemoryBarrier2>(VK_STRUCTURE_TYPE_MEMORY_BARRIER_2);
  mb.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  mb.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  mb.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
  mb.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
  auto di = vkStruct<VkDependencyInfo>(VK_STRUCTURE_TYPE_DEPENDENCY_INFO);
  di.memoryBarrierCount = 1;
  di.pMemoryBarriers = &mb;
  vkCmdPipelineBarrier2(cb_, &di);
  checkVk(vkEndCommandBuffer(cb_), "vkEndCommandBuffer");
  device_.submitAndWait(cb_);
  stamps_.assign(used_, 0);
  if (used_)
    checkVk(vkGetQueryPoolResults(device_.device(), queries_, 0, used_, used_ * sizeof(uint64_t),
                                  stamps_.data(), sizeof(uint64_t),
                                  VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
            "vkGetQueryPoolResults");
}

double GpuCommands::activeMs(uint32_t a, uint32_t b) const {
  double ms = msBetween(a, b);
  for (const auto& [end, start] : gaps_)
    if (end >= a && start <= b) ms -= msBetween(end, start);
  return ms;
}

double GpuCommands::msBetween(uint32_t a, uint32_t b) const {
  if (a >= stamps_.size() || b >= stamps_.size()) return 0;
  return double(stamps_[b] - stamps_[a]) * device_.timestampPeriodNs() * 1e-6;
}

}  // namespace tandem
