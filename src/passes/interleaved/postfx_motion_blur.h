// postfx_motion_blur: post-process motion blur from motion vectors (McGuire, Hennessy, Bukowski &
// Osman 2012, "A reconstruction filter for plausible motion blur"). The sharp image is the scene
// at mid-shutter; each pixel's blur radius is half its displacement over the shutter (clamped to
// the tile size K). TileMax keeps the largest velocity of each K x K tile, NeighborMax the
// largest of the 3 x 3 tiles around; each pixel gathers S samples along its NeighborMax velocity
// (jittered), weighting each by soft depth comparisons and cone / cylinder coverage: blurry
// samples in front reach over, samples behind a blurry pixel stand in for the background it
// uncovers.
// Beyond the paper (Tan et al. 2022's future work, hybrid motion blur): `mb_mask` marks the tiles
// where the post-process is least trustworthy — a neighbourhood mixing motions (a moving object
// crossing or uncovering other geometry: the velocities inside the 3 x 3 tiles differ from the
// largest by more than `mask_threshold` pixels of blur radius), bilinearly widened by a tile so
// that a composite fades between the two images.
// Inputs: hdr (sharp, mid-shutter), velocity (pixels over the whole shutter), view_depth.
// Outputs: mb_postfx, mb_mask.
#pragma once
#include "pipeline/param_table.h"

namespace tandem {

struct PostfxMotionBlurSettings {
  enum class Mask { Spread, Edges };
  int tileSize = 20;  // K
  int samples = 15;   // S
  float softZ = 0.1f;
  float maskThreshold = 1.0f;
  Mask mask = Mask::Spread;
};

// The counters PostfxMotionBlurPass reports each frame (Pass::counters, FrameContext::report).
struct PostfxMotionBlurCounters {
  static constexpr const char* maskedTilesPercent = "postfx_motion_blur/masked_tiles_percent";
};

class PostfxMotionBlurPass : public SettingsPass<PostfxMotionBlurSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* hdr = "hdr";
    static constexpr const char* mbMask = "mb_mask";
    static constexpr const char* mbPostfx = "mb_postfx";
    static constexpr const char* velocity = "velocity";
    static constexpr const char* viewDepth = "view_depth";
  };
  std::string type() const override { return "postfx_motion_blur"; }
  std::string description() const override {
    return "Post-process motion blur: tile max velocity + gather (McGuire et al. 2012); mask of "
           "mixed motion for the hybrid";
  }
  std::vector<BufferSlot> inputs() const override {
    return {{Slots::hdr, 3}, {Slots::velocity, 2, BufferKind::Motion}, {Slots::viewDepth, 1}};
  }
  std::vector<BufferSlot> outputs() const override {
    return {{Slots::mbPostfx, 3}, {Slots::mbMask, 1, BufferKind::Mask}};
  }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/postfx_motion_blur.comp
  void executeGpu(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override;

 protected:
  const ParamTable<PostfxMotionBlurSettings>& tableFor() const override;
};

}  // namespace tandem
