// deferred_shading: Walewski et al. 2019 Listing 5 over the G-buffer, through the one shading
// function (shading/blinn_phong.h); background pixels show the skybox along the camera ray. Inputs:
// position, normal, geo_normal, diffuse, specular, emission, ambient, optical, object_id,
// material_id. Output: hdr (linear radiance). With `shadows` = shadow_map it shades with the
// frame's raster shadow maps, as a rasterizer lights its G-buffer: each light's share weighed
// once, the maps deciding every light that reaches the cull floor, hdr = L - (1 - S) with S
// Listing 8a's shadow term (shadow_tile.h), what blend made of ss_fallback's map shadows, so
// that no later pass evaluates the lights again. A pipeline that traces shadows or takes them from
// ss_fallback cannot use it (Pipeline::validate). On the GPU the same, pixel for pixel.
#pragma once
#include "pipeline/param_table.h"

namespace tandem {

struct DeferredSettings {
  enum class Shadows { Off, ShadowMap };
  Shadows shadows = Shadows::Off;  // Listing 5: unshadowed
  int shadowMapSize = 1024;
  bool shadowMapFit = true;   // FrameContext::shadowMapResolution
  float shadowCull = 0.004f;  // as ss_fallback's and rt_secondary's shadow_cull
};

// The counters DeferredShadingPass reports each frame with map shadows.
struct DeferredCounters {
  static constexpr const char* shadowMapRedraws = "deferred_shading/shadow_map_redraws";
};

class DeferredShadingPass : public SettingsPass<DeferredSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* hdr = "hdr";
    static constexpr const char* objectId = "object_id";
    static constexpr const char* geoNormal = "geo_normal";
  };
  std::string type() const override { return "deferred_shading"; }
  std::string description() const override {
    return "Blinn-Phong lighting of the G-buffer (Listing 5), unshadowed or with shadow maps";
  }
  std::vector<BufferSlot> inputs() const override;
  std::vector<BufferSlot> outputs() const override { return {{Slots::hdr, 3}}; }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/deferred_shading.comp
  void executeGpu(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override;
  bool shadesMapShadows() const override {
    return settings().shadows == DeferredSettings::Shadows::ShadowMap;
  }

 protected:
  const ParamTable<DeferredSettings>& tableFor() const override;

 private:
  void executeShadowed(FrameContext& ctx);
};

}  // namespace tandem
