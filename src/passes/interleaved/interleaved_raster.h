// interleaved_raster: the visibility of interleaved sampling by rasterization, one pass per (time,
// lens) pair of T into the samples that carry it (interleaved.h: what the samples are).
#pragma once
#include "passes/interleaved/interleaved.h"
#include "raster/rasterizer.h"

namespace tandem {

// What interleaved rasterization reports besides InterleavedCounters.
struct InterleavedRasterCounters {
  static constexpr const char* setUpPerPass = "interleaved_raster/triangles_set_up_per_pass";
  static constexpr const char* setUpMax = "interleaved_raster/triangles_set_up_max";
  static constexpr const char* setUpMin = "interleaved_raster/triangles_set_up_min";
  static constexpr const char* staticSetUpOnce = "interleaved_raster/static_triangles_set_up_once";
};

class InterleavedRasterPass : public InterleavedPass {
 public:
  std::string type() const override { return "interleaved_raster"; }
  std::string description() const override {
    return "Interleaved rasterization: one pass per (time, lens) pair of T into the samples "
           "whose tile slot carries it (Foster 2015)";
  }
  std::vector<CounterDesc> counters() const override;
  // The compute rasterizer in sample mode, each pass drawing every object (no static share).
  bool hasGpu() const override { return true; }
  void executeGpu(FrameContext& ctx) override;

 protected:
  void visibility(FrameContext& ctx, const SampleLayout& layout, const std::vector<Camera>& cams,
                  const std::vector<float>& taus, const uint8_t* active,
                  VisibilityBuffer& vis) override;

 private:
  Rasterizer rasterizer_;
  std::vector<uint8_t> cellActive_;  // masked passes: cells holding a needed sample
};

}  // namespace tandem
