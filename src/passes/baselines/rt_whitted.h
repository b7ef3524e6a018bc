// rt_whitted: Whitted ray tracing from the camera with the same effects for every pixel, no
// rasterization and no heuristic (Walewski et al. 2019's "RAYT ONLY"); primary rays as rt_gbuffer
// traces them. Output: hdr. Parameters: the Whitted settings, every shadow traced by default.
// On the GPU (shaders/rt_whitted.comp) pixel for pixel the same, when every shadow is traced.
#pragma once
#include "passes/common/whitted_settings.h"

namespace tandem {

struct RTWhittedSettings {
  WhittedParams whitted{.shadows = ShadowMode::Rays};  // the all-rays baseline
};

class RTWhittedPass : public SettingsPass<RTWhittedSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* hdr = "hdr";
    static constexpr const char* objectId = "object_id";
  };
  std::string type() const override { return "rt_whitted"; }
  std::string description() const override {
    return "Whitted ray tracing of the whole frame (RAYT ONLY)";
  }
  std::vector<BufferSlot> outputs() const override {
    return {{Slots::hdr, 3}, {Slots::objectId, 1, BufferKind::Id}};
  }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/rt_whitted.comp
  void executeGpu(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override { return whittedCounters(*this); }

 protected:
  const ParamTable<RTWhittedSettings>& tableFor() const override;
};

}  // namespace tandem
