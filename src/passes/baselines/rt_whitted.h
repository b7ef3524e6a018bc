// rt_whitted: Whitted ray tracing from the camera with the same effects for every pixel, no
// rasterization and no heuristic (seed 002's "RAYT ONLY"); primary rays as rt_gbuffer traces them.
// Output: hdr. Parameters: max_depth, importance_cutoff.
#pragma once
#include "pipeline/pass.h"

namespace tandem {

class RTWhittedPass : public Pass {
 public:
  std::string type() const override { return "rt_whitted"; }
  std::string description() const override {
    return "Whitted ray tracing of the whole frame (RAYT ONLY)";
  }
  std::vector<BufferSlot> outputs() const override {
    return {{"hdr", 3}, {"object_id", 1, BufferKind::Id}};
  }
  std::vector<ParamDesc> params() const override;
  void execute(FrameContext& ctx) override;
};

}  // namespace tandem
