// nh_denoise: the non-homogeneous denoiser of Peres 2022 §4.4 (Algorithm 1, passes/atrous.h): the
// foveation layers become regions — three (inner, middle, outer: NH3LD), two (inner, and middle
// + outer merged: NH2LD) or one (the whole frame: Base) — filtered one after another, each with
// its own level count and decreasing step widths, over both eyes in one pass. Only pixels the
// binary mask marks as sampled are read; the others are filled from them. With `demodulate` the
// filter runs on the illumination (colour minus emission, over the diffuse albedo; Dammertz's
// optional diffuse-buffer step) and the albedo is multiplied back after.
// Beyond the thesis, `levels_from = variance` sets each region's level count from this frame's
// measured noise: the variance of a listed pixel about its listed neighbours (same surface),
// relative to the mean luminance, over the region's listed share (the noise per pixel area);
// each level widens the footprint about fourfold, so levels = ceil(log4(noise / target)).
// Beyond the thesis too, `split = direct` (the default where a direct_light pass gives pt_direct):
// the filter runs on pt_noisy - pt_direct only (the bounce, the dimmer lights and zero-mean
// light-selection noise) and pt_direct, noise-free at every pixel, is added back unfiltered, so
// the edges of shadows and of a sun patch stay as sharp as the G-buffer; `split = none` filters
// the whole estimate, as the thesis does.
// Inputs: pt_noisy, normal, position, depth, diffuse, emission, fov_mask, fov_layer; optional
// pt_variance, pt_direct. Output: denoised.
#pragma once
#include <utility>
#include <vector>

#include "passes/foveated/atrous.h"
#include "pipeline/param_table.h"

namespace tandem {

struct NHDenoiseSettings {
  enum class Regions { One, Two, Three };  // Base, NH2LD, NH3LD
  enum class ColorWeight { Mean, Variance };
  enum class LevelsFrom { Fixed, Variance };
  enum class Split { None, Direct };
  Regions regions = Regions::Three;
  int levelsInner = 2, levelsMiddle = 3, levelsOuter = 5;  // M, N, P
  float sigmaColor = 16, sigmaNormal = 0.3f, sigmaPosition = 0.05f;
  bool demodulate = true;
  ColorWeight colorWeight = ColorWeight::Mean;
  float sigmaVariance = 4;
  LevelsFrom levelsFrom = LevelsFrom::Fixed;
  // 0.0005: on Table 5's three scenes 0.001 left the accumulated periphery blotchy (one level
  // short of Base's smoothness); halving it was no worse on any scene, one frame or eight.
  float targetVariance = 0.0005f;
  Split split = Split::Direct;
};

// The counters NHDenoisePass reports each frame.
struct NHDenoiseCounters {
  static constexpr const char* levelsRun = "nh_denoise/levels_run";
  static constexpr int kMaxRegions = 3;
  // Levels chosen for region r (levels_from = variance).
  static std::string levelsRegion(int r) { return "nh_denoise/levels_region" + std::to_string(r); }
};

class NHDenoisePass : public SettingsPass<NHDenoiseSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* denoised = "denoised";
    static constexpr const char* depth = "depth";
    static constexpr const char* diffuse = "diffuse";
    static constexpr const char* emission = "emission";
    static constexpr const char* fovLayer = "fov_layer";
    static constexpr const char* fovMask = "fov_mask";
    static constexpr const char* normal = "normal";
    static constexpr const char* position = "position";
    static constexpr const char* ptDirect = "pt_direct";
    static constexpr const char* ptNoisy = "pt_noisy";
    static constexpr const char* ptVariance = "pt_variance";
  };
  std::string type() const override { return "nh_denoise"; }
  std::string description() const override {
    return "Non-homogeneous edge-avoiding À-Trous denoising per foveation layer (Peres 2022 §4.4)";
  }
  std::vector<BufferSlot> inputs() const override;
  std::vector<BufferSlot> outputs() const override {
    return {{Slots::denoised, 3, BufferKind::Color}};
  }
  void execute(FrameContext& ctx) override;
  // shaders/nh_denoise.comp, with either colour weight.
  bool hasGpu() const override { return true; }
  void executeGpu(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override;
  // The (region, step width) of every level the last frame ran, in order (Algorithm 1).
  const std::vector<std::pair<int, int>>& lastSteps() const { return steps_; }

 protected:
  const ParamTable<NHDenoiseSettings>& tableFor() const override;

 private:
  std::vector<std::pair<int, int>> steps_;
  AtrousImage image_;  // planes kept between frames (no reallocation)
};

}  // namespace tandem
