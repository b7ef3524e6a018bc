// mb_composite: the hybrid motion blur image, lerp(mb_postfx, mb_interleaved, mb_mask): the
// post-process blur (postfx_motion_blur) where it can be trusted, interleaved samples (Foster
// 2015, after Fatahalian et al. 2009) inside its mask. Neither paper has it: it extends Tan et al.
// 2022's future work (a hybrid of post-process and ray-traced motion blur) with Aqsis's
// interleaved samples.
// Inputs: mb_postfx, mb_interleaved, mb_mask. Output: hdr.
#pragma once
#include "pipeline/pass.h"

namespace tandem {

class MotionBlurCompositePass : public Pass {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* hdr = "hdr";
    static constexpr const char* mbInterleaved = "mb_interleaved";
    static constexpr const char* mbMask = "mb_mask";
    static constexpr const char* mbPostfx = "mb_postfx";
  };
  std::string type() const override { return "mb_composite"; }
  std::string description() const override {
    return "Hybrid motion blur composite: interleaved samples inside the mask, post-process "
           "outside";
  }
  std::vector<BufferSlot> inputs() const override {
    return {{Slots::mbPostfx, 3}, {Slots::mbInterleaved, 3}, {Slots::mbMask, 1, BufferKind::Mask}};
  }
  std::vector<BufferSlot> outputs() const override { return {{Slots::hdr, 3}}; }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/postfx_motion_blur.comp
  void executeGpu(FrameContext& ctx) override;
};

}  // namespace tandem
