// ss_fallback: what production hybrids draw for the effects the heuristic did not select (Walewski
// et al. 2019 draws them black, Listing 8a). For each pixel of a reflective or transparent object
// whose reflection or refraction was not traced, it looks along the reflected (refracted) direction
// through the frame itself: a world-space march projected on the screen, hitting where it
// passes just behind the depth of the G-buffer, takes the shaded colour there (screen-space
// reflection / refraction); a march that leaves the screen or finds nothing takes the sky.
// Mode "environment" skips the march and takes the sky; mode "probe" (the default: it measures
// best) looks up a small cube map drawn from the object's centre (reflection_probes.h). Unselected
// shadows come from the frame's raster shadow maps (raster/shadow_maps.h, shared with classified
// shadows at the same size) through rt_secondary's classified shadow tile (shadow_tile.h) with the
// maps deciding every pair: the same culling of negligible lights, the same shading of S
// (hybrid-heuristic shades them in deferred_shading instead, its lights weighed once, and turns
// them off here). Both "off" is the paper's rule, for its tables. Inputs: the G-buffer sample
// slots, hdr, heuristic_mask. Output: fallback = reflection RGB, refraction RGB, shadow RGB (eq.
// 4's S), then flags: 1 where reflection/refraction were written, 1 where the shadow was.
#pragma once
#include "passes/heuristic/effect_channels.h"
#include "passes/heuristic/reflection_probes.h"
#include "pipeline/param_table.h"
#include "raster/shadow_maps.h"

namespace tandem {

struct FallbackSettings {
  enum class Mode { Off, Environment, ScreenSpace, Probe };
  enum class Shadows { Off, ShadowMap };
  // Defaults measured (docs/benchmarks.md): probes score best against rt-only on the heuristic
  // scenes (SSIM and FLIP; the sky and the screen-space march tie below them).
  Mode mode = Mode::Probe;
  Shadows shadows = Shadows::ShadowMap;
  int shadowMapSize = 1024;
  bool shadowMapFit = true;   // FrameContext::shadowMapResolution
  float shadowCull = 0.004f;  // as rt_secondary's shadow_cull (WhittedParams)
  int probeSize = 128;
  int maxProbes = 32;
  int probeRefresh = 2;
  bool probeBake = true;  // every mirror and glass object's probe on the first frame
  int steps = 32;
  float thickness = 0.05f;
};

// The counters ScreenSpaceFallbackPass reports each frame (Pass::counters, FrameContext::report).
struct FallbackCounters {
  static constexpr const char* probesDrawn = "ss_fallback/probes_drawn";
  static constexpr const char* shadowMapRedraws = "ss_fallback/shadow_map_redraws";
};

class ScreenSpaceFallbackPass : public SettingsPass<FallbackSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* fallback = "fallback";
    static constexpr const char* geoNormal = "geo_normal";
    static constexpr const char* hdr = "hdr";
    static constexpr const char* heuristicMask = "heuristic_mask";
    static constexpr const char* normal = "normal";
    static constexpr const char* objectId = "object_id";
    static constexpr const char* optical = "optical";
    static constexpr const char* position = "position";
  };
  std::string type() const override { return "ss_fallback"; }
  bool addsShadows() const override {
    return settings().shadows == FallbackSettings::Shadows::ShadowMap;
  }
  std::string description() const override {
    return "Screen-space reflection/refraction (or sky) where no ray was traced";
  }
  std::vector<BufferSlot> inputs() const override;
  std::vector<BufferSlot> outputs() const override { return {fallback::slot()}; }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/fallback.comp
  void executeGpu(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override;
  void resetHistory() override {
    probes_ = {};
    deviceProbes_ = {};
  }

 protected:
  const ParamTable<FallbackSettings>& tableFor() const override;

 private:
  // Brings the probes of the reflective and transparent objects in view up to date.
  void updateProbes(FrameContext& ctx, const ShadingContext& shading);
  // The same given each object's pixels (`area`, 2 x objects): [0, objects) those that show an
  // untraced reflection or refraction, [objects, 2 x objects) all reflective or transparent ones.
  void updateProbes(FrameContext& ctx, const ShadingContext& shading,
                    const std::vector<uint32_t>& area, ReflectionProbes& probes);
  ReflectionProbes probes_, deviceProbes_;  // the CPU's, the GPU's
};

}  // namespace tandem
