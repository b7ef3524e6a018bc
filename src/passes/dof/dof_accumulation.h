// dof_accumulation: temporal accumulation of the ray-traced DoF (Tan et al. 2022 §3.2.3), at the
// ray mask's resolution. The near and far fields are accumulated apart, each premultiplied by its
// share of the rays (so the merge is normalised by the accumulated hit ratio h):
//   near history follows the motion vectors (Rosado 2008);
//   far history follows the mean far-field world position of the pixel's rays, or of its 3x3
//   neighbourhood's when its own rays saw none, projected into last frame's camera;
// blended by an exponential moving average (history weight 0.95; a young history averages its
// frames equally, so a static shot converges to the mean of its inputs). The merged colour is
// lerp(far, near, h) — with this frame's hit ratio where the pixel moves (§3.2.3: no far-field
// ghosts inside near silhouettes). Temporal moments of each frame's merged luminance (Schied et
// al. 2017) give the variance of the accumulated mean (the noise left), Gaussian-blurred for the
// next frame's ray mask and the reconstruction.
// Beyond the paper (`adaptive_alpha`): a per-pixel blend factor from the temporal gradient
// (Schied et al. 2018): where this frame's 3x3 mean luminance departs from the history's by more
// than the noise explains, the history weight drops, so moved or changed content does not ghost;
// on by default: along the camera paths it measures better or equal on every shot (`tandem
// experiment hybrid-dof`, docs/benchmarks.md).
// Inputs: rt_near, rt_far, rt_hit, rt_far_position, motion; history: acc_near, acc_far,
// acc_moments. Outputs: those three, rt_color (rgb, CoC, hit ratio, coverage), dof_variance.
#pragma once
#include "pipeline/param_table.h"

namespace tandem {

struct DofAccumulationSettings {
  float historyWeight = 0.95f;
  float motionPixels = 0.25f;
  bool adaptiveAlpha = true;
  float varianceBlur = 1;
};

// The counters DofAccumulationPass reports each frame (Pass::counters, FrameContext::report).
struct DofAccumulationCounters {
  static constexpr const char* meanVariance = "dof_accumulation/mean_variance";
  static constexpr const char* varianceAbove1e6 = "dof_accumulation/variance_above_1e-6";
};

class DofAccumulationPass : public SettingsPass<DofAccumulationSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* accFar = "acc_far";
    static constexpr const char* accMoments = "acc_moments";
    static constexpr const char* accNear = "acc_near";
    static constexpr const char* dofVariance = "dof_variance";
    static constexpr const char* motion = "motion";
    static constexpr const char* rtColor = "rt_color";
    static constexpr const char* rtFar = "rt_far";
    static constexpr const char* rtFarPosition = "rt_far_position";
    static constexpr const char* rtHit = "rt_hit";
    static constexpr const char* rtNear = "rt_near";
  };
  std::string type() const override { return "dof_accumulation"; }
  std::string description() const override {
    return "Temporal accumulation of near/far ray-traced DoF, reprojected, variance (Tan et al. "
           "2022 "
           "§3.2.3)";
  }
  std::vector<BufferSlot> inputs() const override;
  std::vector<BufferSlot> outputs() const override;
  void execute(FrameContext& ctx) override;
  // shaders/dof_accumulation.comp, the variance's blur by convolve.comp (dof_accumulation_gpu.cpp)
  bool hasGpu() const override { return true; }
  void executeGpu(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override;

 protected:
  const ParamTable<DofAccumulationSettings>& tableFor() const override;
};

}  // namespace tandem
