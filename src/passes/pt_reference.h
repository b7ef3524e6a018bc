// pt_reference: the ground-truth renderer (issue 4, first part) — `spp` path-traced samples per
// pixel (rt/path_tracer.h), jittered over the pixel and over the thin lens (a pinhole when the
// camera's aperture is 0), averaged into hdr. Each pixel draws from its
// own PCG stream keyed by the frame seed and pixel index, so the image does not depend on the
// thread count. Output: hdr. Parameters: spp, max_depth.
#pragma once
#include "pipeline/pass.h"

namespace tandem {

class PTReferencePass : public Pass {
 public:
  std::string type() const override { return "pt_reference"; }
  std::string description() const override {
    return "Reference path tracing (NEE to punctual lights, emission, sky, roulette)";
  }
  std::vector<BufferSlot> outputs() const override { return {{"hdr", 3}}; }
  std::vector<ParamDesc> params() const override;
  void execute(FrameContext& ctx) override;
};

}  // namespace tandem
