// The graphics pipeline's visibility draw: the hardware rasterizer drawing each object's triangles
// (pulled from the scene by gl_VertexIndex, no vertex buffers) into a triangle-id colour
// attachment and a reversed-Z depth attachment, copied into buffers for raster_pack.comp to turn
// into the compute rasterizer's visibility keys. It exists to be measured against the compute
// rasterizer (raster_gbuffer's `gpu_rasterizer`): on a GPU whose graphics stages run on a few of
// its units the compute one may win. Dynamic rendering (Vulkan 1.3), so no render passes.
#pragma once
#include <volk.h>

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "gpu/gpu_device.h"
#include "gpu/gpu_memory.h"
#include "gpu/shaders/raster_graphics_args.h"

namespace tandem {

class GpuGraphicsRaster {
 public:
  // A GpuError when the device's queue has no graphics or lacks the attachments' formats.
  explicit GpuGraphicsRaster(GpuDevice& device);
  ~GpuGraphicsRaster();
  GpuGraphicsRaster(const GpuGraphicsRaster&) = delete;
  GpuGraphicsRaster& operator=(const GpuGraphicsRaster&) = delete;

  struct Draw {
    uint32_t object = 0, triangles = 0;
  };
  // Records into `cb` the draw of `draws` (each with `args`, its object set) into w x h
  // attachments cleared to nothing, then their copy into `ids` (a uint a pixel: 0 nothing, else
  // the triangle's index + 1) and `depths` (a float a pixel), visible to compute and copies after.
  void record(VkCommandBuffer cb, int width, int height, RasterDrawArgs args,
              const std::vector<Draw>& draws, const GpuBuffer& ids, const GpuBuffer& depths);

 private:
  struct Target {
    VkImage color = VK_NULL_HANDLE, depth = VK_NULL_HANDLE;
    VkImageView colorView = VK_NULL_HANDLE, depthView = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
  };
  // The attachments of one size, made on first use and kept (a frame's views share a few sizes).
  Target& target(int width, int height);
  GpuDevice& device_;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  std::map<std::pair<int, int>, Target> targets_;
};

}  // namespace tandem
