#include "gpu/gpu_memory.h"

#include <algorithm>

namespace tandem {

GpuMemory::~GpuMemory() {
  for (Block& b : blocks_)
    if (b.memory) vkFreeMemory(device_.device(), b.memory, nullptr);
}

uint32_t GpuMemory::memoryType(uint32_t allowed, MemoryUse use) const {
  VkPhysicalDeviceMemoryProperties mem;
  vkGetPhysicalDeviceMemoryProperties(device_.physical(), &mem);
  auto first = [&](VkMemoryPropertyFlags want) {
    for (uint32_t i = 0; i < mem.memoryTypeCount; ++i)
      if ((allowed & (1u << i)) && (mem.memoryTypes[i].propertyFlags & want) == want) return int(i);
    return -1;
  };
  constexpr VkMemoryPropertyFlags kHost =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  int type = -1;
  if (use == MemoryUse::Device) {
    type = first(VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (type < 0) type = first(0);  // no device-local type for this buffer: any allowed one
  } else {
    if (use == MemoryUse::Readback) type = first(kHost | VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
    if (type < 0) type = first(kHost);
  }
  if (type < 0) throw GpuError("GPU: no host-visible memory type for a staging buffer");
  return uint32_t(type);
}

VkMemoryPropertyFlags GpuMemory::properties(const GpuBuffer& b) const {
  if (b.block < 0) return 0;
  VkPhysicalDeviceMemoryProperties mem;
  vkGetPhysicalDeviceMemoryProperties(device_.physical(), &mem);
  return mem.memoryTypes[blocks_[size_t(b.block)].type].propertyFlags;
}

bool GpuMemory::carve(Block& b, VkDeviceSize size, VkDeviceSize align, VkDeviceSize* offset) {
  for (size_t k = 0; k < b.free.size(); ++k) {
    auto [start, length] = b.free[k];
    const VkDeviceSize aligned = (start + align - 1) / align * align;
    if (aligned + size > start + length) continue;
    *offset = aligned;
    // What is left before and after the carved range stays free.
    std::vector<std::pair<VkDeviceSize, VkDeviceSize>> rest;
    if (aligned > start) rest.push_back({start, aligned - start});
    if (aligned + size < start + length)
      rest.push_back({aligned + size, start + length - aligned - size});
    b.free.erase(b.free.begin() + std::ptrdiff_t(k));
    b.free.insert(b.free.begin() + std::ptrdiff_t(k), rest.begin(), rest.end());
    return true;
  }
  return false;
}

GpuBuffer GpuMemory::allocate(VkDeviceSize bytes, MemoryUse use) {
  const bool hostVisible = use != MemoryUse::Device;
  VkDevice dev = device_.device();
  // What no allocation could hold is refused before Vulkan is asked (it must not be).
  const VkDeviceSize limit =
      std::min(device_.info().maxBufferBytes, device_.info().deviceLocalBytes);
  if (bytes > limit)
    throw GpuError("GPU: out of device memory: a buffer of " + std::to_string(bytes >> 20) +
                   " MiB is more than " + device_.info().name + " can hold (" +
                   std::to_string(limit >> 20) + " MiB)");
  GpuBuffer out;
  out.size = std::max<VkDeviceSize>(bytes, 4);
  VkBufferCreateInfo bi{};
  bi.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  bi.size = out.size;
  bi.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
             VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
  bi.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  checkVk(vkCreateBuffer(dev, &bi, nullptr, &out.buffer), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(dev, out.buffer, &req);
  try {
    const uint32_t type = memoryType(req.memoryTypeBits, use);
    int found = -1;
    for (size_t i = 0; i < blocks_.size() && found < 0; ++i)
      if (blocks_[i].type == type && (!hostVisible || blocks_[i].mapped) &&
          carve(blocks_[i], req.size, req.alignment, &out.offset))
        found = int(i);
    if (found < 0) {
      Block b;
      b.type = type;
      b.size = std::min(std::max(kBlockBytes, (req.size + 65535) / 65536 * 65536),
                        std::max(limit, req.size));
      VkMemoryAllocateFlagsInfo flags{};
      flags.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO;
      flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
      VkMemoryAllocateInfo ai{};
      ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
      ai.pNext = &flags;
      ai.allocationSize = b.size;
      ai.memoryTypeIndex = type;
      const VkResult r = vkAllocateMemory(dev, &ai, nullptr, &b.memory);
      if (r != VK_SUCCESS)
        throw GpuError("GPU: out of device memory: " + std::to_string(b.size >> 20) +
                       " MiB could not be allocated beside the " +
                       std::to_string(allocatedBytes() >> 20) + " MiB held (" +
                       device_.info().name + ")");
      if (hostVisible) checkVk(vkMapMemory(dev, b.memory, 0, b.size, 0, &b.mapped), "vkMapMemory");
      b.free.push_back({0, b.size});
      blocks_.push_back(b);
      found = int(blocks_.size() - 1);
      carve(blocks_.back(), req.size, req.alignment, &out.offset);
    }
    Block& b = blocks_[size_t(found)];
    checkVk(vkBindBufferMemory(dev, out.buffer, b.memory, out.offset), "vkBindBufferMemory");
    out.block = found;
    if (b.mapped) out.mapped = static_cast<char*>(b.mapped) + out.offset;
    VkBufferDeviceAddressInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO;
    ai.buffer = out.buffer;
    out.address = vkGetBufferDeviceAddress(dev, &ai);
    // Keep the carved size (the requirement's) for release.
    out.size = std::max(out.size, req.size);
  } catch (...) {
    vkDestroyBuffer(dev, out.buffer, nullptr);
    throw;
  }
  return out;
}

void GpuMemory::release(GpuBuffer& buf) {
  if (!buf) return;
  vkDestroyBuffer(device_.device(), buf.buffer, nullptr);
  if (buf.block >= 0) {
    auto& free = blocks_[size_t(buf.block)].free;
    free.push_back({buf.offset, buf.size});
    std::sort(free.begin(), free.end());
    // Neighbouring free ranges become one.
    std::vector<std::pair<VkDeviceSize, VkDeviceSize>> merged;
    for (const auto& r : free)
      if (!merged.empty() && merged.back().first + merged.back().second == r.first)
        merged.back().second += r.second;
      else
        merged.push_back(r);
    free = std::move(merged);
  }
  buf = GpuBuffer{};
}

VkDeviceSize GpuMemory::allocatedBytes() const {
  VkDeviceSize n = 0;
  for (const Block& b : blocks_) n += b.size;
  return n;
}

}  // namespace tandem
