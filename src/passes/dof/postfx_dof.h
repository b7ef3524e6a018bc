// postfx_dof: the post-process depth of field of Tan et al. 2022 §3.1 (Jimenez 2014 as the paper
// adapts it), at half resolution:
//  1. downsample: colour (2x2 mean), CoC (the nearest of the four: the near field wins at
//     silhouettes) and a high-specular flag (specular >= specular_threshold);
//  2. tile max CoC over 8x8 half-res tiles and its 3x3-tile neighbourhood max: the gather radius;
//  3. 9-tap bilateral prefilter, which is also the colour's downsampling filter: bilinear taps
//     of the frame, diameter 1/8 of the neighbourhood's max CoC (never below √2 frame pixels,
//     so the taps do not fall on the same pixel), weighted by CoC similarity;
//  4. 81-tap main filter: the centre and four rings of 8, 16, 24, 32 taps scaled to the
//     neighbourhood max; a tap reaches the centre when its CoC radius covers the distance
//     (D(0, i)), the background's CoC clamped to the centre's so it never blurs over sharper
//     foreground; foreground (nearer by more than depth_range) and background weighted by the
//     sample alpha 1 / (π r²) and combined by eq. 1's normalised weighted sum (not Jimenez's
//     alpha, §3.1); the bokeh intensity is the share of reaching taps that are highlights;
//     the ring pattern turns by a per-frame angle (the paper jitters; TAA resolves it);
//  5. 3x3 median, then a bilinear upscale to the frame.
// With apertureBlades >= 3 (beyond the paper, parameter `polygon`) D(0, i) tests the tap against
// the aperture polygon's bokeh instead of a disk, as the reference's lens samples spread.
// Inputs: hdr (sharp colour), coc, specular. Outputs: postfx (colour), bokeh (intensity, and the
// share of the gather's weight from foreground taps: where a blurred foreground spreads).
#pragma once
#include "passes/dof/dof_common.h"
#include "pipeline/param_table.h"
#include "shading/gbuffer_layout.h"

namespace tandem {

struct PostfxDofSettings {
  float depthRange = 0.1f;  // metres
  float specularThreshold = 0.5f;
  float bokehLuminance = 1;
  bool polygon = true;
  bool median = true;
};

class PostfxDofPass : public SettingsPass<PostfxDofSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* bokeh = "bokeh";
    static constexpr const char* coc = "coc";
    static constexpr const char* hdr = "hdr";
    static constexpr const char* postfx = "postfx";
    static constexpr const char* specular = "specular";
  };
  std::string type() const override { return "postfx_dof"; }
  std::string description() const override {
    return "Post-process gather DoF: half res, tile max CoC, 9-tap prefilter, 81-tap gather "
           "(eq. 1), bokeh intensity, 3x3 median (Tan et al. 2022 §3.1)";
  }
  std::vector<BufferSlot> inputs() const override {
    return {{Slots::hdr, 3}, {Slots::coc, 1, BufferKind::Signed}, gbufferSlot(Slots::specular)};
  }
  std::vector<BufferSlot> outputs() const override {
    return {{Slots::postfx, 3}, dof::BokehChannels::slot()};
  }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/postfx_dof.comp, postfx_dof_gpu.cpp
  void executeGpu(FrameContext& ctx) override;

 protected:
  const ParamTable<PostfxDofSettings>& tableFor() const override;
};

}  // namespace tandem
