// rt_gbuffer: the same G-buffer as raster_gbuffer, produced by primary rays (8-ray packets over
// 4x2 pixel blocks) through Embree; back faces of single-sided materials are culled like the
// rasterizer does; on the GPU the same, pixel for pixel. Inputs: none. Outputs: the G-buffer
// targets. Parameters: none.
#pragma once
#include "pipeline/pass.h"

namespace tandem {

class RTGBufferPass : public Pass {
 public:
  std::string type() const override { return "rt_gbuffer"; }
  std::string description() const override { return "G-buffer from primary rays (Embree packets)"; }
  std::vector<BufferSlot> outputs() const override;
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/rt_gbuffer.comp
  void executeGpu(FrameContext& ctx) override;
};

}  // namespace tandem
