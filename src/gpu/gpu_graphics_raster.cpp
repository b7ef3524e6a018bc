#include "gpu/gpu_graphics_raster.h"

#include <string>

#include "gpu/shaders/raster_graphics_frag_spv.h"
#include "gpu/shaders/raster_graphics_vert_spv.h"

namespace tandem {

namespace {
constexpr VkFormat kIdFormat = VK_FORMAT_R32_UINT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

VkShaderModule shaderModule(VkDevice dev, const uint32_t* words, size_t count) {
  auto si = vkStruct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
  si.codeSize = count * 4;
  si.pCode = words;
  VkShaderModule m = VK_NULL_HANDLE;
  checkVk(vkCreateShaderModule(dev, &si, nullptr, &m), "vkCreateShaderModule");
  return m;
}

void requireFormat(VkPhysicalDevice pd, VkFormat format, VkFormatFeatureFlags need,
                   const char* what) {
  VkFormatProperties p;
  vkGetPhysicalDeviceFormatProperties(pd, format, &p);
  if ((p.optimalTilingFeatures & need) != need)
    throw GpuError(std::string("GPU: the graphics rasterizer needs ") + what);
}

VkImageMemoryBarrier2 imageBarrier(VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                                   VkImageLayout to, VkPipelineStageFlags2 srcStage,
                                   VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                                   VkAccessFlags2 dstAccess) {
  auto b = vkStruct<VkImageMemoryBarrier2>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2);
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, 0, 1, 0, 1};
  return b;
}

void barriers(VkCommandBuffer cb, const VkMemoryBarrier2* memory,
              const std::vector<VkImageMemoryBarrier2>& images) {
  auto di = vkStruct<VkDependencyInfo>(VK_STRUCTURE_TYPE_DEPENDENCY_INFO);
  di.memoryBarrierCount = memory ? 1 : 0;
  di.pMemoryBarriers = memory;
  di.imageMemoryBarrierCount = uint32_t(images.size());
  di.pImageMemoryBarriers = images.data();
  vkCmdPipelineBarrier2(cb, &di);
}
}  // namespace

GpuGraphicsRaster::GpuGraphicsRaster(GpuDevice& device) : device_(device) {
  VkPhysicalDevice pd = device.physical();
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, families.data());
  if (device.queueFamily() >= n ||
      !(families[device.queueFamily()].queueFlags & VK_QUEUE_GRAPHICS_BIT))
    throw GpuError("GPU: the graphics rasterizer needs a queue with graphics; " +
                   device.info().name + "'s compute queue has none");
  requireFormat(pd, kIdFormat, VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT, "R32_UINT attachments");
  requireFormat(pd, kDepthFormat, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT,
                "D32_SFLOAT depth attachments");
  VkDevice dev = device.device();
  VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                            uint32_t(sizeof(RasterDrawArgs))};
  auto li = vkStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
  li.pushConstantRangeCount = 1;
  li.pPushConstantRanges = &range;
  checkVk(vkCreatePipelineLayout(dev, &li, nullptr, &layout_), "vkCreatePipelineLayout");

  VkShaderModule vert =
      shaderModule(dev, kRasterGraphicsVertSpv, sizeof(kRasterGraphicsVertSpv) / 4);
  VkShaderModule frag =
      shaderModule(dev, kRasterGraphicsFragSpv, sizeof(kRasterGraphicsFragSpv) / 4);
  VkPipelineShaderStageCreateInfo stages[2] = {};
  for (int i = 0; i < 2; ++i) {
    stages[i].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    stages[i].stage = i == 0 ? VK_SHADER_STAGE_VERTEX_BIT : VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[i].module = i == 0 ? vert : frag;
    stages[i].pName = "main";
  }
  auto vi = vkStruct<VkPipelineVertexInputStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
  auto ia = vkStruct<VkPipelineInputAssemblyStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  auto vp = vkStruct<VkPipelineViewportStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
  vp.viewportCount = vp.scissorCount = 1;
  auto rs = vkStruct<VkPipelineRasterizationStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  // The CPU culls back faces: counter-clockwise in the world is front (y turned down in the
  // vertex stage keeps Vulkan's counter-clockwise the same triangles).
  rs.cullMode = VK_CULL_MODE_BACK_BIT;
  rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  rs.lineWidth = 1.0f;
  auto ms = vkStruct<VkPipelineMultisampleStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  auto ds = vkStruct<VkPipelineDepthStencilStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
  ds.depthTestEnable = ds.depthWriteEnable = VK_TRUE;
  ds.depthCompareOp = VK_COMPARE_OP_GREATER;  // reversed Z: greater is nearer, cleared to 0
  VkPipelineColorBlendAttachmentState blend{};
  blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT;
  auto cbs = vkStruct<VkPipelineColorBlendStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
  cbs.attachmentCount = 1;
  cbs.pAttachments = &blend;
  const VkDynamicState dyn[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  auto dy = vkStruct<VkPipelineDynamicStateCreateInfo>(
      VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO);
  dy.dynamicStateCount = 2;
  dy.pDynamicStates = dyn;
  auto ri =
      vkStruct<VkPipelineRenderingCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO);
  ri.colorAttachmentCount = 1;
  ri.pColorAttachmentFormats = &kIdFormat;
  ri.depthAttachmentFormat = kDepthFormat;
  auto ci =
      vkStruct<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &ri);
  ci.stageCount = 2;
  ci.pStages = stages;
  ci.pVertexInputState = &vi;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cbs;
  ci.pDynamicState = &dy;
  ci.layout = layout_;
  const VkResult r = vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline_);
  vkDestroyShaderModule(dev, vert, nullptr);
  vkDestroyShaderModule(dev, frag, nullptr);
  if (r != VK_SUCCESS) {
    vkDestroyPipelineLayout(dev, layout_, nullptr);
    checkVk(r, "creating the graphics rasterizer");
  }
}

GpuGraphicsRaster::~GpuGraphicsRaster() {
  VkDevice dev = device_.device();
  for (auto& [size, t] : targets_) {
    vkDestroyImageView(dev, t.colorView, nullptr);
    vkDestroyImageView(dev, t.depthView, nullptr);
    vkDestroyImage(dev, t.color, nullptr);
    vkDestroyImage(dev, t.depth, nullptr);
    vkFreeMemory(dev, t.memory, nullptr);
  }
  vkDestroyPipeline(dev, pipeline_, nullptr);
  vkDestroyPipelineLayout(dev, layout_, nullptr);
}

GpuGraphicsRaster::Target& GpuGraphicsRaster::target(int width, int height) {
  auto it = targets_.find({width, height});
  if (it != targets_.end()) return it->second;
  VkDevice dev = device_.device();
  Target t;
  auto make = [&](VkFormat format, VkImageUsageFlags usage, VkImage* image) {
    auto ii = vkStruct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
    ii.imageType = VK_IMAGE_TYPE_2D;
    ii.format = format;
    ii.extent = {uint32_t(width), uint32_t(height), 1};
    ii.mipLevels = ii.arrayLayers = 1;
    ii.samples = VK_SAMPLE_COUNT_1_BIT;
    ii.tiling = VK_IMAGE_TILING_OPTIMAL;
    ii.usage = usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    ii.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    checkVk(vkCreateImage(dev, &ii, nullptr, image), "vkCreateImage");
  };
  make(kIdFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, &t.color);
  make(kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, &t.depth);
  VkMemoryRequirements rc, rd;
  vkGetImageMemoryRequirements(dev, t.color, &rc);
  vkGetImageMemoryRequirements(dev, t.depth, &rd);
  const VkDeviceSize depthOffset = (rc.size + rd.alignment - 1) / rd.alignment * rd.alignment;
  VkPhysicalDeviceMemoryProperties mp;
  vkGetPhysicalDeviceMemoryProperties(device_.physical(), &mp);
  const uint32_t allowed = rc.memoryTypeBits & rd.memoryTypeBits;
  uint32_t type = ~0u;
  for (uint32_t i = 0; i < mp.memoryTypeCount && type == ~0u; ++i)
    if ((allowed & (1u << i)) &&
        (mp.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT))
      type = i;
  for (uint32_t i = 0; i < mp.memoryTypeCount && type == ~0u; ++i)
    if (allowed & (1u << i)) type = i;
  auto ai = vkStruct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
  ai.allocationSize = depthOffset + rd.size;
  ai.memoryTypeIndex = type;
  if (type == ~0u || vkAllocateMemory(dev, &ai, nullptr, &t.memory) != VK_SUCCESS) {
    vkDestroyImage(dev, t.color, nullptr);
    vkDestroyImage(dev, t.depth, nullptr);
    throw GpuError("GPU: out of device memory for the graphics rasterizer's " +
                   std::to_string(width) + "x" + std::to_string(height) + " attachments");
  }
  checkVk(vkBindImageMemory(dev, t.color, t.memory, 0), "vkBindImageMemory");
  checkVk(vkBindImageMemory(dev, t.depth, t.memory, depthOffset), "vkBindImageMemory");
  auto view = [&](VkImage image, VkFormat format, VkImageAspectFlags aspect, VkImageView* out) {
    auto vi = vkStruct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
    vi.image = image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = format;
    vi.subresourceRange = {aspect, 0, 1, 0, 1};
    checkVk(vkCreateImageView(dev, &vi, nullptr, out), "vkCreateImageView");
  };
  view(t.color, kIdFormat, VK_IMAGE_ASPECT_COLOR_BIT, &t.colorView);
  view(t.depth, kDepthFormat, VK_IMAGE_ASPECT_DEPTH_BIT, &t.depthView);
  return targets_.emplace(std::make_pair(width, height), t).first->second;
}

void GpuGraphicsRaster::record(VkCommandBuffer cb, int width, int height, RasterDrawArgs args,
                               const std::vector<Draw>& draws, const GpuBuffer& ids,
                               const GpuBuffer& depths) {
  const Target& t = target(width, height);
  // What compute and copies wrote (the scene, its refits) is read by the draw; the attachments'
  // last copy is done before they are drawn again.
  auto before = vkStruct<VkMemoryBarrier2>(VK_STRUCTURE_TYPE_MEMORY_BARRIER_2);
  before.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT;
  before.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;
  before.dstStageMask =
      VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
  before.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
  const VkPipelineStageFlags2 tests =
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  barriers(cb, &before,
           {imageBarrier(t.color, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                         VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                         0, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                         VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT),
            imageBarrier(t.depth, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                         VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                         0, tests,
                         VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                             VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT)});
  auto color = vkStruct<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
  color.imageView = t.colorView;
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.clearValue.color.uint32[0] = 0;
  auto depth = vkStruct<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
  depth.imageView = t.depthView;
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  depth.clearValue.depthStencil = {0.0f, 0};
  auto ri = vkStruct<VkRenderingInfo>(VK_STRUCTURE_TYPE_RENDERING_INFO);
  ri.renderArea = {{0, 0}, {uint32_t(width), uint32_t(height)}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 1;
  ri.pColorAttachments = &color;
  ri.pDepthAttachment = &depth;
  vkCmdBeginRendering(cb, &ri);
  vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
  const VkViewport viewport{0, 0, float(width), float(height), 0, 1};
  const VkRect2D scissor{{0, 0}, {uint32_t(width), uint32_t(height)}};
  vkCmdSetViewport(cb, 0, 1, &viewport);
  vkCmdSetScissor(cb, 0, 1, &scissor);
  for (const Draw& d : draws) {
    args.object = d.object;
    vkCmdPushConstants(cb, layout_, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof args, &args);
    vkCmdDraw(cb, 3 * d.triangles, 1, 0, 0);
  }
  vkCmdEndRendering(cb);
  barriers(
      cb, nullptr,
      {imageBarrier(t.color, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_READ_BIT),
       imageBarrier(t.depth, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, tests,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT)});
  VkBufferImageCopy copy{};
  copy.imageExtent = {uint32_t(width), uint32_t(height), 1};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  vkCmdCopyImageToBuffer(cb, t.color, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, ids.buffer, 1, &copy);
  copy.imageSubresource.aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT;
  vkCmdCopyImageToBuffer(cb, t.depth, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, depths.buffer, 1,
                         &copy);
  auto after = vkStruct<VkMemoryBarrier2>(VK_STRUCTURE_TYPE_MEMORY_BARRIER_2);
  after.srcStageMask = VK_PIPELINE_STAGE_2_TRANSFER_BIT;
  after.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
  after.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT;
  after.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT;
  barriers(cb, &after, {});
}

}  // namespace tandem
