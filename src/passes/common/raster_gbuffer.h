// raster_gbuffer: rasterizes the frame's scene into the visibility buffer, then resolves each
// covered pixel once into the G-buffer (Walewski et al. 2019 §3.1, Listings 1-3). Inputs: none
// (scene). Outputs: the G-buffer targets (raster/gbuffer.h). Parameters: on the GPU, which
// rasterizer draws the visibility (the compute one, the CPU's triangles and depths; or the graphics
// pipeline's hardware rasterizer, to measure one against the other).
#pragma once
#include "passes/common/gbuffer_writer.h"
#include "passes/common/gpu_visible_surfaces.h"
#include "passes/common/visible_surfaces.h"
#include "pipeline/param_table.h"
#include "pipeline/pass.h"

namespace tandem {

class RasterGBufferPass : public SettingsPass<RasterizerSettings> {
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

 protected:
  const ParamTable<RasterizerSettings>& tableFor() const override { return rasterizerTable(); }

 private:
  VisibleSurfaces surfaces_;
  GBufferWriter writer_;
  GpuVisibleSurfaces gpuSurfaces_;
};

}  // namespace tandem
