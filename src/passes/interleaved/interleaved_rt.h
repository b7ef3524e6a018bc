// interleaved_rt: the visibility of interleaved sampling by ray tracing, each sample's primary ray
// at its pair's time and lens point (interleaved.h: what the samples are).
#pragma once
#include "passes/interleaved/interleaved.h"

namespace tandem {

class InterleavedRTPass : public InterleavedPass {
 public:
  std::string type() const override { return "interleaved_rt"; }
  std::string description() const override {
    return "Interleaved ray tracing: each sample's primary ray at its pair's time and lens point "
           "(Foster 2015, the same tiles)";
  }

  // shaders/interleaved.comp, at either shading rate.
  bool hasGpu() const override { return true; }
  void executeGpu(FrameContext& ctx) override;

 protected:
  void visibility(FrameContext& ctx, const SampleLayout& layout, const std::vector<Camera>& cams,
                  const std::vector<float>& taus, const uint8_t* active,
                  VisibilityBuffer& vis) override;
  bool tracesPrimaryRays() const override { return true; }
};

}  // namespace tandem
