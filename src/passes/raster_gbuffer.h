// raster_gbuffer: rasterizes the frame's scene into the visibility buffer, then resolves each
// covered pixel once into the G-buffer (seed 002 §3.1, Listings 1-3). Inputs: none (scene).
// Outputs: the G-buffer targets (raster/gbuffer.h). Parameters: none.
#pragma once
#include <vector>

#include "pipeline/pass.h"
#include "raster/rasterizer.h"

namespace tandem {

class RasterGBufferPass : public Pass {
 public:
  std::string type() const override { return "raster_gbuffer"; }
  std::string description() const override {
    return "Software-rasterized visibility buffer resolved into the G-buffer";
  }
  std::vector<BufferSlot> outputs() const override;
  void execute(FrameContext& ctx) override;

  // The last frame's visibility buffer of each view and the rasterizer's figures (all views).
  const std::vector<VisibilityBuffer>& visibility() const { return visibility_; }
  const RasterStats& stats() const { return stats_; }

 private:
  Rasterizer rasterizer_;  // binning scratch reused across frames
  std::vector<VisibilityBuffer> visibility_;
  RasterStats stats_;
};

}  // namespace tandem
