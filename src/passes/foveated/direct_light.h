// direct_light (beyond Peres 2022): the direct light of the primary surfaces, noise-free, for the
// denoiser to keep apart from what it filters. For every pixel of every view (listed by the
// foveation or not): its emission plus its diffuse albedo times the light of the `lights` lights
// that give it the most unshadowed light, each with its shadow ray (rt/diffuse_gi.h,
// brightestDirect); the sky where there is no surface. That is what the foveated path tracer's
// next-event estimate averages to for those lights, so pt_noisy - pt_direct is the light left
// to filter (the bounce and the dimmer lights, plus zero-mean selection noise): nh_denoise with
// `split = direct` filters only that and adds pt_direct back, so shadow edges and a sun patch
// stay as sharp as the G-buffer.
// Inputs: position, normal, geo_normal, diffuse, emission, depth. Output: pt_direct.
#pragma once
#include "pipeline/param_table.h"

namespace tandem {

struct DirectLightSettings {
  int lights = 4;  // [0, 64]: lights traced per pixel, the brightest there first
};

class DirectLightPass : public SettingsPass<DirectLightSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* ptDirect = "pt_direct";
  };
  std::string type() const override { return "direct_light"; }
  std::string description() const override {
    return "Noise-free direct light of the brightest lights at every pixel (beyond Peres 2022)";
  }
  std::vector<BufferSlot> inputs() const override;
  std::vector<BufferSlot> outputs() const override {
    return {{Slots::ptDirect, 3, BufferKind::Color}};
  }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/direct_light.comp
  void executeGpu(FrameContext& ctx) override;

 protected:
  const ParamTable<DirectLightSettings>& tableFor() const override;
};

}  // namespace tandem
