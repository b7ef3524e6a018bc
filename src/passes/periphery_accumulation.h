// periphery_accumulation (beyond seed 004): temporal accumulation of the path-traced samples
// outside the fovea. Each listed pixel of a layer >= from_layer blends this frame's estimate into
// its history, reprojected by the motion vectors (nearest pixel of the same eye) and kept only
// where last frame saw the same surface there (world positions within position_tolerance of the
// eye distance): an exponential moving average whose young history averages its frames equally
// (weight max(1 / (n + 1), alpha_min)). The fovea keeps this frame's samples alone (no lag where
// the viewer looks). Unlisted pixels stay empty for the denoiser.
// Inputs: pt_noisy, fov_mask, fov_layer, motion, position, depth, optional pt_variance; history:
// pt_history. Outputs: pt_accum (the estimate the denoiser reads), pt_accum_variance (this frame's
// variance over the frames averaged, for the denoiser's variance-guided weights; -1 where
// unknown), pt_history (rgb, count, world position).
#pragma once
#include "pipeline/pass.h"

namespace tandem {

class PeripheryAccumulationPass : public Pass {
 public:
  std::string type() const override { return "periphery_accumulation"; }
  std::string description() const override {
    return "Temporal accumulation with reprojection outside the fovea (beyond seed 004)";
  }
  std::vector<BufferSlot> inputs() const override;
  std::vector<BufferSlot> outputs() const override {
    return {{"pt_accum", 3, BufferKind::Color},
            {"pt_accum_variance", 1, BufferKind::Variance},
            {"pt_history", 7, BufferKind::List}};
  }
  std::vector<ParamDesc> params() const override;
  void execute(FrameContext& ctx) override;
};

}  // namespace tandem
