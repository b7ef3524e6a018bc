// tonemap: linear HDR radiance -> display sRGB in [0,1]. Exposure scales by 2^EV, then the
// operator maps to [0,1]: clamp (none), reinhard (x / (1 + x)) or aces (Narkowicz 2015 fit of
// the ACES filmic curve), then the sRGB transfer function.
// Input: hdr. Output: output. Parameters: exposure, operator.
#pragma once
#include "core/math.h"
#include "pipeline/pass.h"

namespace tandem {

enum class ToneOperator { Clamp = 0, Reinhard = 1, Aces = 2 };

// The per-pixel mapping, shared with AOV output of HDR buffers.
Vec3 tonemapPixel(Vec3 hdr, float exposureEV, ToneOperator op);

class TonemapPass : public Pass {
 public:
  std::string type() const override { return "tonemap"; }
  std::string description() const override { return "Exposure, tone curve and sRGB encoding"; }
  std::vector<BufferSlot> inputs() const override { return {{"hdr", 3}}; }
  std::vector<BufferSlot> outputs() const override { return {{"output", 3}}; }
  std::vector<ParamDesc> params() const override;
  void execute(FrameContext& ctx) override;
};

}  // namespace tandem
