// vbuffer_shading: deferred shading straight from the visibility buffer. The frame is
// rasterized into a visibility buffer (depth, object and triangle per pixel: 12 B/px), and each
// pixel is resolved and shaded in one pass, the resolved surface going into a shading batch
// instead of a 136 B/px G-buffer that the next pass reads back. The same resolve and the same
// shading kernel as raster_gbuffer + deferred_shading, so the image is the same; what it lacks
// is the G-buffer (use `deferred` for G-buffer views and passes that read it).
// Inputs: none (scene). Outputs: hdr, depth, object_id. Parameters: none.
#pragma once
#include "passes/visible_surfaces.h"
#include "pipeline/pass.h"

namespace tandem {

class VBufferShadingPass : public Pass {
 public:
  std::string type() const override { return "vbuffer_shading"; }
  std::string description() const override {
    return "Blinn-Phong lighting straight from the visibility buffer (no G-buffer)";
  }
  std::vector<BufferSlot> outputs() const override {
    return {{"hdr", 3}, {"depth", 1, BufferKind::Depth}, {"object_id", 1, BufferKind::Id}};
  }
  void execute(FrameContext& ctx) override;

 private:
  VisibleSurfaces surfaces_;
};

}  // namespace tandem
