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

  // shaders/interleaved.comp; a pixel's shading rate (shared samples) stays on the CPU.
  bool hasGpu() const override {
    return settings().shadingRate == InterleavedSettings::ShadingRate::Sample;
  }
  std::string gpuCondition() const override { return "with `shading_rate = sample`"; }
  void executeGpu(FrameContext& ctx) override;

 protected:
  void visibility(FrameContext& ctx, const SampleLayout& layout, const std::vector<Camera>& cams,
                  const std::vector<float>& taus, const uint8_t* active,
                  VisibilityBuffer& vis) override;
  bool tracesPrimaryRays() const override { return true; }
};

}  // namespace tandem
