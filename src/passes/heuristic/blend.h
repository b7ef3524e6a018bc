// blend: Walewski et al. 2019 §3.4 (Listing 10). Outside the heuristic mask the lighting L is kept;
// inside, C = L - (1 - S) (eq. 4) and the result is the average of C_M and C_R (eq. 5-6). With the
// per-effect mask, an effect not traced for a pixel counts as absent (O_M or O_R = 0) unless
// the optional `fallback` (ss_fallback) has a screen-space or sky colour for it.
// Inputs: hdr (L), shadow, reflection, refraction, optical, heuristic_mask, fallback (optional).
// Output: composite.
#pragma once
#include "passes/heuristic/effect_channels.h"
#include "pipeline/pass.h"
#include "shading/gbuffer_layout.h"

namespace tandem {

class BlendPass : public Pass {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* composite = "composite";
    static constexpr const char* fallback = "fallback";
    static constexpr const char* hdr = "hdr";
    static constexpr const char* heuristicMask = "heuristic_mask";
    static constexpr const char* optical = "optical";
    static constexpr const char* reflection = "reflection";
    static constexpr const char* refraction = "refraction";
    static constexpr const char* shadow = "shadow";
  };
  std::string type() const override { return "blend"; }
  std::string description() const override {
    return "Combine lighting with ray-traced effects (eq. 4-6)";
  }
  std::vector<BufferSlot> inputs() const override {
    return {{Slots::hdr, 3},
            {Slots::shadow, 3},
            {Slots::reflection, 3},
            {Slots::refraction, 3},
            gbufferSlot(Slots::optical),
            effectSlot(Slots::heuristicMask, BufferKind::Mask),
            optionalFallback()};
  }
  std::vector<BufferSlot> outputs() const override { return {{Slots::composite, 3}}; }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/blend.comp
  void executeGpu(FrameContext& ctx) override;

 private:
  static BufferSlot optionalFallback() {
    BufferSlot s = fallback::slot();
    s.optional = true;
    return s;
  }
};

}  // namespace tandem
