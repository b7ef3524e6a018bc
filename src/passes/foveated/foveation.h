// foveation: the foveated sample distribution (Peres 2022 §4.2, passes/foveation_map.h), computed
// once per configuration and again only when a parameter, the eye's size or the gaze changes —
// as in the thesis it is not part of a frame's work (the frame that recomputes it reports
// counter foveation/recomputed = 1; benchmarks warm up past it). One distribution serves both
// eyes. Outputs: fov_coords (the coordinate buffer: one eye's listed pixels as (x, y, spp)
// records), fov_mask (the binary mask over the dual image), fov_layer (0 inner, 1 middle,
// 2 outer; the overlay view). mode = full is Base: every pixel listed with spp_inner samples.
// The gaze follows the scene's gazeTrace (at the frame's time) when it has one, else gaze_x/y.
#pragma once
#include "passes/foveated/foveation_map.h"
#include "pipeline/param_table.h"

namespace tandem {

struct FoveationSettings {
  enum class Mode { Foveated, Full };
  enum class Gaze { Trace, Fixed };
  Mode mode = Mode::Foveated;
  float r0 = 144, r1 = 288;  // pixels at 1080 rows
  float p = 0.5f;
  float outerP = -1;
  int sppInner = 4, sppMiddle = 3, sppOuter = 2;
  Gaze gaze = Gaze::Trace;
  float gazeX = 0.5f, gazeY = 0.5f;
  bool scaleRadii = true;
  int seed = 0;
  bool rotate = false;
};

// The channels of fov_coords, one record per listed pixel: its coordinates in the eye's image and
// the samples it takes.
struct CoordChannels {
  static constexpr int kX = 0, kY = 1, kSpp = 2, kCount = 3;
  static BufferSlot slot() {
    return BufferSlot{"fov_coords", 0, BufferKind::List, Extent::any()}.named({"x", "y", "spp"});
  }
};

// The counters FoveationPass reports each frame (Pass::counters, FrameContext::report).
struct FoveationCounters {
  static constexpr const char* recomputed = "foveation/recomputed";
  static constexpr const char* listed = "foveation/listed";
  static constexpr const char* samples = "foveation/samples";
};

class FoveationPass : public SettingsPass<FoveationSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* fovCoords = "fov_coords";
    static constexpr const char* fovLayer = "fov_layer";
    static constexpr const char* fovMask = "fov_mask";
  };
  std::string type() const override { return "foveation"; }
  std::string description() const override {
    return "Foveated sample distribution: 3 layers, coordinate buffer + binary mask (Peres 2022 "
           "§4.2)";
  }
  std::vector<BufferSlot> outputs() const override {
    return {CoordChannels::slot(),
            {Slots::fovMask, 1, BufferKind::Mask},
            {Slots::fovLayer, 1, BufferKind::Id}};
  }
  void execute(FrameContext& ctx) override;
  // The distribution built on the host, moved to the device when it changes.
  bool hasGpu() const override { return true; }
  void executeGpu(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override;
  // The distribution the parameters describe for an eye of width x height (what execute uses).
  FoveationDesc desc(int width, int height) const;
  const FoveationMap& map() const { return map_; }

 protected:
  const ParamTable<FoveationSettings>& tableFor() const override;

 private:
  // The distribution for this frame, rebuilt if its description changed (whether it was), its
  // counters reported; and its buffers written on the host.
  bool update(FrameContext& ctx);
  void write(FrameContext& ctx);
  FoveationMap map_;
  FoveationDesc built_;
  bool valid_ = false;
  const float* written_ = nullptr;  // the mask buffer last written (rewritten when it changes)
};

}  // namespace tandem
