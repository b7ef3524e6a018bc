// deferred_shading: Walewski et al. 2019 Listing 5 over the G-buffer, through the one shading
// function (shading/blinn_phong.h); background pixels show the skybox along the camera ray. Inputs:
// position, normal, geo_normal, diffuse, specular, emission, ambient, optical, object_id,
// material_id. Output: hdr (linear radiance). Parameters: none. On the GPU the same, pixel for
// pixel.
#pragma once
#include "pipeline/pass.h"

namespace tandem {

class DeferredShadingPass : public Pass {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* hdr = "hdr";
  };
  std::string type() const override { return "deferred_shading"; }
  std::string description() const override {
    return "Blinn-Phong lighting of the G-buffer (Listing 5)";
  }
  std::vector<BufferSlot> inputs() const override;
  std::vector<BufferSlot> outputs() const override { return {{Slots::hdr, 3}}; }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/deferred_shading.comp
  void executeGpu(FrameContext& ctx) override;
};

}  // namespace tandem
