// dof_reconstruction: median and spatial reconstruction of the accumulated ray-traced DoF (Tan et
// al. 2022 §3.2.4), at its resolution. A 3x3 median first removes sparse unconverged bokeh; then a
// circular kernel (the centre and two rings of 8 and 16 taps) scaled to the pixel's accumulated
// CoC gathers its neighbours from the mip level lod = clamp(c_t·0.05, 0, 3) (eq. 8), rejecting
// taps whose own CoC radius is smaller than their distance; the pixel's colour and hit ratio are
// lerped towards the gathered ones by b = clamp(σ²·2000, 0, 0.9) (eq. 5), so converged pixels
// keep their detail and noisy ones are blurred.
// Inputs: rt_color (dof::RtChannels), dof_variance. Output: rt_recon (the same channels).
#pragma once
#include "passes/dof/dof_common.h"
#include "pipeline/param_table.h"

namespace tandem {

struct DofReconstructionSettings {
  float varianceWeight = 2000;
  float lodScale = 0.05f;
  bool median = true;
};

class DofReconstructionPass : public SettingsPass<DofReconstructionSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* dofVariance = "dof_variance";
    static constexpr const char* rtColor = "rt_color";
    static constexpr const char* rtRecon = "rt_recon";
  };
  std::string type() const override { return "dof_reconstruction"; }
  std::string description() const override {
    return "Median + spatial reconstruction of ray-traced DoF, eq. 5 and 8 (Tan et al. 2022 "
           "§3.2.4)";
  }
  std::vector<BufferSlot> inputs() const override {
    return {dof::RtChannels::slot(Slots::rtColor),
            {Slots::dofVariance, 1, BufferKind::Variance, Extent::any()}};
  }
  std::vector<BufferSlot> outputs() const override {
    return {dof::RtChannels::slot(Slots::rtRecon)};
  }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/dof_reconstruction.comp
  void executeGpu(FrameContext& ctx) override;

 protected:
  const ParamTable<DofReconstructionSettings>& tableFor() const override;
};

}  // namespace tandem
