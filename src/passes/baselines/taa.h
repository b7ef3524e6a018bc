// taa: temporal anti-aliasing (Karis 2014, "High-quality temporal supersampling"). Each frame
// the projection is jittered by the next point of the Halton (2, 3) sequence; the pass
// reprojects last frame's result through the motion vectors (Catmull-Rom), clamps it to the
// current 3x3 neighbourhood's box in YCoCg (so disoccluded or changed pixels do not ghost), and
// blends with the current frame (weight `alpha`, rising to `motion_alpha` for pixels moving
// `motion_pixels` per frame, since resampled history blurs; weights divided by 1 + luma so a
// bright sample does not flicker). After a history reset, or where the reprojected point leaves the
// view, the current frame is taken as is. With `converge`, the first frames after a reset are
// averaged equally (the current frame's weight 1/n, never below alpha), so a short sequence is
// not dominated by its first aliased frame. Inputs: hdr (jittered colour), motion; history input:
// taa (last frame's result). Output: taa.
#pragma once
#include "pipeline/param_table.h"

namespace tandem {

struct TAASettings {
  enum class Filter { Bilinear, CatmullRom };
  float alpha = 0.1f;
  int jitterPhases = 8;
  float motionAlpha = 0.2f;
  float motionPixels = 8;
  bool clamp = true;
  Filter filter = Filter::CatmullRom;
  bool converge = false;
};

class TAAPass : public SettingsPass<TAASettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* hdr = "hdr";
    static constexpr const char* motion = "motion";
    static constexpr const char* taa = "taa";
  };
  std::string type() const override { return "taa"; }
  std::string description() const override {
    return "Temporal anti-aliasing: jitter, reprojection, YCoCg neighbourhood clamp (Karis 2014)";
  }
  std::vector<BufferSlot> inputs() const override;
  std::vector<BufferSlot> outputs() const override { return {{Slots::taa, 3}}; }
  void request(FrameRequest& r) const override;
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }
  void executeGpu(FrameContext& ctx) override;  // shaders/taa.comp
  void resetHistory() override { framesAveraged_ = 0; }

 protected:
  const ParamTable<TAASettings>& tableFor() const override;

 private:
  int framesAveraged_ = 0;  // frames in the history since it was last reset
};

}  // namespace tandem
