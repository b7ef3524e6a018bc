// foveated_pt: path tracing over the coordinate buffer only (Peres 2022 §4.3): for every listed
// pixel of both eyes (one parallel dispatch over the list twice, the right eye offset by the left
// eye's width) and each of its samples, one path of rt/diffuse_gi.h from the G-buffer's primary
// surface: a shadow ray to a random light, one cosine-weighted bounce with its own shadow ray,
// Lambertian BRDF. Pixels not listed stay empty (0) for the denoiser to fill; the sky is seen in
// the pixel's camera direction. Samples are Owen-scrambled Sobol, seeded per frame, so each frame
// draws fresh noise. Inputs: the G-buffer (position, normal, geo_normal, diffuse, emission,
// depth), fov_coords. Outputs: pt_noisy (the mean of the pixel's samples) and pt_variance (the
// variance of that mean's luminance, from the samples' spread; -1 for a single sample).
// `light_selection`: uniform (the thesis) or grid (beyond it: rt/light_grid.h, each light by its
// estimated irradiance where the path is; the grid is built once and kept while the lights stay).
#pragma once
#include <cstdint>
#include <memory>

#include "pipeline/param_table.h"
#include "rt/light_grid.h"
#include "shading/blinn_phong.h"

namespace tandem {

struct FoveatedPTSettings {
  enum class LightSelection { Uniform, Grid };
  LightSelection lightSelection = LightSelection::Grid;
};

// The counters FoveatedPTPass reports each frame (Pass::counters, FrameContext::report).
struct FoveatedPTCounters {
  static constexpr const char* lightGridBuilt = "foveated_pt/light_grid_built";
  static constexpr const char* lightGridProbeRays = "foveated_pt/light_grid_probe_rays";
  static constexpr const char* samples = "foveated_pt/samples";
};

class FoveatedPTPass : public SettingsPass<FoveatedPTSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* fovCoords = "fov_coords";
    static constexpr const char* ptNoisy = "pt_noisy";
    static constexpr const char* ptVariance = "pt_variance";
  };
  std::string type() const override { return "foveated_pt"; }
  std::string description() const override {
    return "Path tracing over the coordinate buffer: NEE + one diffuse bounce (Peres 2022 §4.3)";
  }
  std::vector<BufferSlot> inputs() const override;
  std::vector<BufferSlot> outputs() const override {
    return {{Slots::ptNoisy, 3, BufferKind::Color}, {Slots::ptVariance, 1, BufferKind::Variance}};
  }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/foveated_pt.comp
  void executeGpu(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override;

 protected:
  const ParamTable<FoveatedPTSettings>& tableFor() const override;

 private:
  // The black-materials warning once a scene, and the light grid (null: uniform selection),
  // built when the lights change: what both devices do before tracing.
  const LightGrid* prepare(FrameContext& ctx, const ShadingContext& shading);
  std::unique_ptr<LightGrid> grid_;
  uint64_t gridKey_ = 0;
  const void* gridScene_ = nullptr;
  const void* warnedScene_ = nullptr;  // the scene whose black (metal) materials were reported
};

}  // namespace tandem
