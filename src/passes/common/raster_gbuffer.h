// raster_gbuffer: rasterizes the frame's scene into the visibility buffer, then resolves each
// covered pixel once into the G-buffer (Walewski et al. 2019 §3.1, Listings 1-3). Inputs: none
// (scene). Outputs: the G-buffer targets (raster/gbuffer.h). Parameters: none.
#pragma once
#include "passes/common/gbuffer_writer.h"
#include "passes/common/gpu_visible_surfaces.h"
#include "passes/common/visible_surfaces.h"
#include "pipeline/pass.h"

namespace tandem {

class RasterGBufferPass : public Pass {
 public:
  std::string type() const override { return "raster_gbuffer"; }
  std::string description() const override {
    return "Software-rasterized visibility buffer resolved into the G-buffer";
  }
  std::vector<BufferSlot> outputs() const override;
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // compute rasterizer: gpu_visible_surfaces.h
  void executeGpu(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override { return RasterCounters::all(); }

 private:
  VisibleSurfaces surfaces_;
  GBufferWriter writer_;
  GpuVisibleSurfaces gpuSurfaces_;
};

}  // namespace tandem
