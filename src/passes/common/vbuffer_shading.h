// vbuffer_shading: deferred shading straight from the visibility buffer. The frame is
// rasterized into a visibility buffer (depth, object and triangle per pixel: 12 B/px), and each
// pixel is resolved and shaded in one pass, the resolved surface going into a shading batch
// instead of a 136 B/px G-buffer that the next pass reads back. The same resolve and the same
// shading kernel as raster_gbuffer + deferred_shading, so the image is the same. The G-buffer is
// still written, by the same resolve, when something reads it (a pass, an AOV, the viewer's
// shown buffer): `deferred` is this pass, and its G-buffer views cost only when shown.
// Inputs: none (scene). Outputs: hdr and raster_gbuffer's targets. Parameters: on the GPU, which
// rasterizer draws the visibility (RasterizerSettings).
#pragma once
#include "passes/common/gbuffer_writer.h"
#include "passes/common/gpu_visible_surfaces.h"
#include "passes/common/visible_surfaces.h"
#include "pipeline/pass.h"

namespace tandem {

class VBufferShadingPass : public SettingsPass<RasterizerSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* hdr = "hdr";
  };
  std::string type() const override { return "vbuffer_shading"; }
  std::string description() const override {
    return "Blinn-Phong lighting straight from the visibility buffer (G-buffer written only when "
           "read)";
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
