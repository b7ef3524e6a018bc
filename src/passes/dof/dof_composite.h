// dof_composite: the final depth-of-field image (Tan et al. 2022 §3.3, eq. 7). Inside the zone of
// focus
// (|CoC| < √2) the sharp raster colour — unless a blurred foreground reaches over the pixel
// (some of its lens rays hit the near field, or the gather's foreground share is not 0): the
// pixel is then part of a near-field silhouette (taking the paper's rule literally cuts every
// blurred foreground off at its own outline over an in-focus background). Such a pixel is
// composited like the far field (eq. 7; `silhouette = eq7`) or, by default (beyond the paper,
// measured better), as lerp(sharp, traced near field, h): the lens share 1 − h that sees past
// the foreground sees exactly the sharp raster colour, which half-resolution rays only blur.
// Outside it, in the near field the ray-traced colour
// (accurate see-through silhouettes) lerped towards the post-process colour by the bokeh
// intensity (bright bokeh converge poorly when traced); in the far field the ray-traced colour
// lerped towards the post-process colour by smoothstep(0, 0.3, h) of the hit ratio (eq. 7).
// Where no ray has reached a pixel yet (outside the mask, no history), the post-process colour.
// The ray-traced image is upsampled bilinearly from its resolution. Beyond the paper
// (`fine_coc`, measured better): out of focus but with |CoC| below fine_coc px, where nothing
// nearer spreads over the pixel (no foreground share in the gather; in the far field also no
// near-field ray hit), the sharp image gathered over the CoC disc at full resolution, blended in
// fully below fine_coc / 2: the half-resolution rays and gather, upsampled, blur what a small CoC
// leaves almost sharp. ray_mask sends no rays where this gather takes the pixel wholly.
// `mode = rt` (the rt-dof baseline): the ray-traced colour wherever it exists, the sharp raster
// elsewhere. Without an rt_recon input (postfx-dof): the post-process colour out of focus.
// Inputs: hdr (sharp colour), coc; optional: postfx and bokeh (without them the sharp colour
// stands in: rt-dof has no post-process), rt_recon. Output: dof.
#pragma once
#include "passes/dof/dof_common.h"
#include "pipeline/param_table.h"

namespace tandem {

struct DofCompositeSettings {
  enum class Mode { Hybrid, Rt };
  enum class Silhouette { Eq7, SharpBackground };
  Mode mode = Mode::Hybrid;
  float farBlend = 0.3f;
  bool bokeh = true;
  Silhouette silhouette = Silhouette::SharpBackground;
  float fineCoc = dof::kFineCocDefault;  // frame pixels
};

class DofCompositePass : public SettingsPass<DofCompositeSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* bokeh = "bokeh";
    static constexpr const char* coc = "coc";
    static constexpr const char* dof = "dof";
    static constexpr const char* hdr = "hdr";
    static constexpr const char* postfx = "postfx";
    static constexpr const char* rtRecon = "rt_recon";
  };
  std::string type() const override { return "dof_composite"; }
  std::string description() const override {
    return "Composite: sharp raster in the zone of focus, ray-traced near field, post-process "
           "bokeh, far field by hit ratio (Tan et al. 2022 §3.3, eq. 7)";
  }
  std::vector<BufferSlot> inputs() const override {
    BufferSlot rt = dof::RtChannels::slot(Slots::rtRecon);
    BufferSlot postfx{Slots::postfx, 3}, bokeh = dof::BokehChannels::slot();
    rt.optional = postfx.optional = bokeh.optional = true;
    return {{Slots::hdr, 3}, {Slots::coc, 1, BufferKind::Signed}, postfx, bokeh, rt};
  }
  std::vector<BufferSlot> outputs() const override { return {{Slots::dof, 3}}; }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/dof_composite.comp
  void executeGpu(FrameContext& ctx) override;

 protected:
  const ParamTable<DofCompositeSettings>& tableFor() const override;
};

}  // namespace tandem
