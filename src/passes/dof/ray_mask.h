// ray_mask: how many lens rays each pixel of the ray-traced DoF gets (Tan et al. 2022 §3.2.1).
// The G-buffer's inverse view depth (d / z with d the focus distance: like a depth buffer, and
// independent of the scene's units) and normals are Gaussian-filtered (σ = 1 px), reduced to the
// mask's resolution and differentiated by a 5x5 Sobel: x = (δ_d + δ_n)·s (eq. 2), x_n = saturate(1
// − 1/(x + 1)) (eq. 3), x_f = saturate(x_n + σ²·variance_weight)·m (eq. 4) with σ² last frame's
// blurred luminance variance of the accumulated ray-traced image (history input dof_variance);
// rounded, and at least one ray in every near-field pixel (CoC < −√2). Beyond the paper: `dilate`
// also gives one ray to every pixel within the neighbourhood's largest near-field CoC radius of a
// near-field pixel (§5.3's fix for the tiling of Fig. 8b: a blurred foreground spreads that far
// over the background; off: at the paper's variance weight the mask is already full there, measured
// no gain). Also beyond the paper, `fine_coc`: no rays where dof_composite takes the pixel wholly
// from its full-resolution gather of the sharp image (every frame pixel of the mask pixel with
// |CoC| < fine_coc / 2 and no foreground share in the post-process gather, optional input bokeh),
// the near-field minimum included: rays there would not be seen. `mode = all` gives every pixel m
// rays (the rt-dof baseline). Inputs: position, normal, depth, coc; optional: bokeh; history:
// dof_variance. Output: ray_mask (rays per pixel, at half the frame's resolution or the frame's:
// `resolution`).
#pragma once
#include "passes/dof/dof_common.h"
#include "pipeline/param_table.h"

namespace tandem {

struct RayMaskSettings {
  enum class Mode { Adaptive, All };
  enum class Resolution { Half, Full };
  int m = 10;  // the ray budget
  float s = 0.8f;
  float varianceWeight = 100000;
  bool dilate = false;
  Mode mode = Mode::Adaptive;
  float fineCoc = dof::kFineCocDefault;
  Resolution resolution = Resolution::Half;
};

// The counters RayMaskPass reports each frame (Pass::counters, FrameContext::report).
struct RayMaskCounters {
  static constexpr const char* raysPerPixel = "ray_mask/rays_per_pixel";
  static constexpr const char* maskedShare = "ray_mask/masked_share";
};

class RayMaskPass : public SettingsPass<RayMaskSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* bokeh = "bokeh";
    static constexpr const char* coc = "coc";
    static constexpr const char* depth = "depth";
    static constexpr const char* dofVariance = "dof_variance";
    static constexpr const char* normal = "normal";
    static constexpr const char* position = "position";
    static constexpr const char* rayMask = "ray_mask";
  };
  std::string type() const override { return "ray_mask"; }
  std::string description() const override {
    return "Adaptive ray mask: Gaussian + 5x5 Sobel on depth and normals, eq. 2-4, variance "
           "(Tan et al. 2022 §3.2.1)";
  }
  std::vector<BufferSlot> inputs() const override;
  std::vector<BufferSlot> outputs() const override {
    return {{Slots::rayMask, 1, BufferKind::Count, Extent::any()}};
  }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/ray_mask.comp, ray_mask_gpu.cpp
  void executeGpu(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override;

 protected:
  const ParamTable<RayMaskSettings>& tableFor() const override;
};

}  // namespace tandem
