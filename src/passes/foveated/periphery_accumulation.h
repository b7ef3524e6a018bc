// periphery_accumulation (beyond Peres 2022): temporal accumulation of the path-traced samples
// outside the fovea. Each listed pixel of a layer >= from_layer blends this frame's estimate into
// its history: an exponential moving average whose young history averages its frames equally
// (weight max(1 / (n + 1), alpha_min)). The history is reprojected by the motion vectors,
// bilinear over those of the four history pixels of the same eye that saw the same surface
// (world positions within position_tolerance of the eye distance, normals within
// normal_tolerance), none if they cover under a quarter of the footprint. It holds illumination
// (colour over the diffuse albedo, `demodulate`), so texture is always this frame's. With
// `fill_unlisted`, a pixel the foveation did not list this frame takes its reprojected history
// alone, and pt_accum_mask marks it sampled for the denoiser; on a still camera nothing changes
// (an unlisted pixel never had history). The fovea keeps this frame's samples alone (no lag where
// the viewer looks).
// Inputs: pt_noisy, fov_mask, fov_layer, motion, position, normal, depth, diffuse, emission,
// optional pt_variance; history: pt_history. Outputs: pt_accum (the estimate the denoiser reads),
// pt_accum_variance (this frame's variance over the frames averaged, for the denoiser's
// variance-guided weights; -1 where unknown), pt_accum_mask (pixels with an estimate),
// pt_history (illumination rgb, frames, world position, normal).
#pragma once
#include "pipeline/param_table.h"

namespace tandem {

// The channels of pt_history, one record per pixel: the accumulated illumination, the frames
// it averages, and the world position and normal of the surface it belongs to.
struct HistoryChannels {
  static constexpr int kIllumination = 0, kFrames = 3, kPosition = 4, kNormal = 7, kCount = 10;
  static BufferSlot slot() {
    return BufferSlot{"pt_history", 0, BufferKind::List}.named(
        {"r", "g", "b", "frames", "x", "y", "z", "nx", "ny", "nz"});
  }
};

struct PeripheryAccumulationSettings {
  int fromLayer = 1;
  float alphaMin = 0.1f;
  float positionTolerance = 0.02f;
  float normalTolerance = 25;  // degrees
  bool demodulate = true;
  bool fillUnlisted = true;
};

// The counters PeripheryAccumulationPass reports each frame (Pass::counters, FrameContext::report).
struct PeripheryAccumulationCounters {
  static constexpr const char* meanFrames = "periphery_accumulation/mean_frames";
};

class PeripheryAccumulationPass : public SettingsPass<PeripheryAccumulationSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* depth = "depth";
    static constexpr const char* diffuse = "diffuse";
    static constexpr const char* emission = "emission";
    static constexpr const char* fovLayer = "fov_layer";
    static constexpr const char* fovMask = "fov_mask";
    static constexpr const char* motion = "motion";
    static constexpr const char* normal = "normal";
    static constexpr const char* position = "position";
    static constexpr const char* ptAccum = "pt_accum";
    static constexpr const char* ptAccumMask = "pt_accum_mask";
    static constexpr const char* ptAccumVariance = "pt_accum_variance";
    static constexpr const char* ptHistory = "pt_history";
    static constexpr const char* ptNoisy = "pt_noisy";
    static constexpr const char* ptVariance = "pt_variance";
  };
  std::string type() const override { return "periphery_accumulation"; }
  std::string description() const override {
    return "Temporal accumulation with reprojection outside the fovea (beyond Peres 2022)";
  }
  std::vector<BufferSlot> inputs() const override;
  std::vector<BufferSlot> outputs() const override {
    return {{Slots::ptAccum, 3, BufferKind::Color},
            {Slots::ptAccumVariance, 1, BufferKind::Variance},
            {Slots::ptAccumMask, 1, BufferKind::Mask},
            HistoryChannels::slot()};
  }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/periphery_accumulation.comp
  void executeGpu(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override;

 protected:
  const ParamTable<PeripheryAccumulationSettings>& tableFor() const override;
};

}  // namespace tandem
