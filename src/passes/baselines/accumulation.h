// accumulation: the brute-force baseline for depth of field and motion blur (Haeberli & Akeley
// 1990's accumulation buffer). The scene is rasterized N whole times, each at one (time, lens)
// pair — objects where they are at shutter fraction tau (and the camera moved along its shutter
// path), the view moved to a lens point with the projection sheared so the focus plane stays put —
// each image resolved and shaded with the one shading function, and the N images averaged.
// Pairs: times stratified over the shutter, lens points stratified over the aperture (disk or the
// camera's n-gon, Hammersley points), the two decorrelated by a seeded permutation.
// Each image is also offset by a sub-pixel jitter (Halton (2, 3), in a third independent order), so
// the average is anti-aliased like the reference's pixel-area samples.
// Output: hdr. Parameters: samples, mode (dof, motion_blur, both), antialias, shading (local:
// Blinn-Phong without shadows; whitted: the ray-traced shading of the interleaved passes).
#pragma once
#include <vector>

#include "pipeline/param_table.h"
#include "raster/rasterizer.h"
#include "raster/sample_tiles.h"

namespace tandem {

struct AccumulationSettings {
  enum class Mode { Dof, MotionBlur, Both };
  enum class Shading { Whitted, Local };
  int samples = 64;
  Mode mode = Mode::Both;
  bool antialias = true;
  Shading shading = Shading::Local;
};

// The counters AccumulationPass reports each frame (Pass::counters, FrameContext::report).
struct AccumulationCounters {
  static constexpr const char* trianglesBinned = "accumulation/triangles_binned";
};

class AccumulationPass : public SettingsPass<AccumulationSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* hdr = "hdr";
  };
  std::string type() const override { return "accumulation"; }
  std::string description() const override {
    return "Averages N rasterized images at stratified (time, lens) pairs (DoF / motion-blur "
           "baseline)";
  }
  std::vector<BufferSlot> outputs() const override { return {{Slots::hdr, 3}}; }
  void execute(FrameContext& ctx) override;
  // The compute rasterizer and shaders/accumulation.comp.
  bool hasGpu() const override { return true; }
  void executeGpu(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override;

 protected:
  const ParamTable<AccumulationSettings>& tableFor() const override;

 private:
  Rasterizer rasterizer_;
  VisibilityBuffer visibility_;
};

}  // namespace tandem
