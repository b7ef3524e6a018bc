// tonemap: linear HDR radiance -> display sRGB in [0,1]. Exposure scales by 2^EV, then the
// operator maps to [0,1]: clamp (none), reinhard (x / (1 + x)) or aces (Narkowicz 2015 fit of
// the ACES filmic curve), then the sRGB transfer function.
// Input: hdr. Output: output. Parameters: exposure, operator.
#pragma once
#include "core/color.h"
#include "pipeline/param_table.h"

namespace tandem {

struct TonemapSettings {
  float exposure = 0;
  ToneOperator op = ToneOperator::Aces;
};

class TonemapPass : public SettingsPass<TonemapSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* hdr = "hdr";
    static constexpr const char* output = "output";
  };
  std::string type() const override { return "tonemap"; }
  std::string description() const override { return "Exposure, tone curve and sRGB encoding"; }
  std::vector<BufferSlot> inputs() const override { return {{Slots::hdr, 3}}; }
  std::vector<BufferSlot> outputs() const override {
    return {{Slots::output, 3, BufferKind::Display}};
  }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }
  void executeGpu(FrameContext& ctx) override;  // shaders/tonemap.comp

 protected:
  const ParamTable<TonemapSettings>& tableFor() const override;
};

}  // namespace tandem
