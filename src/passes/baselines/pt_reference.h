// pt_reference: the ground-truth renderer (rt/reference_render.h) — path-traced samples per
// pixel (rt/path_tracer.h) from Owen-scrambled Sobol points over the pixel, the thin lens (or
// polygonal aperture), the shutter interval and the path, accumulated progressively up to `spp`
// or `time_limit`. Deterministic for the frame seed whatever the thread or process count.
// Outputs: hdr (the mean) and variance (of the mean's luminance: the noise left).
// Parameters: spp, time_limit, max_depth, progress, accumulate, frame_spp. With `accumulate`
// (the viewer's progressive mode) each frame adds `frame_spp` samples to the last frame's while
// the camera and geometry stay the same, up to `spp`, and starts over on a history reset (scene,
// size, pipeline, lens, max_depth), a camera move or moved geometry. Stereo: one render per eye.
#pragma once
#include <functional>

#include "pipeline/param_table.h"
#include "rt/reference_render.h"
#include "scene/view.h"

namespace tandem {

struct PTReferenceSettings {
  int spp = 1024;
  double timeLimit = 0;  // seconds
  int maxDepth = 16;
  bool progress = true;
  bool accumulate = false;
  int frameSpp = 4;
  Integrator integrator = Integrator::Path;
  int whittedDepth = 10;
};

// The counters PTReferencePass reports each frame (Pass::counters, FrameContext::report).
struct PTReferenceCounters {
  static constexpr const char* spp = "spp";
};

class PTReferencePass : public SettingsPass<PTReferenceSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* hdr = "hdr";
    static constexpr const char* variance = "variance";
  };
  std::string type() const override { return "pt_reference"; }
  std::string description() const override {
    return "Progressive reference path tracing (NEE + MIS, thin lens, motion blur, Sobol)";
  }
  std::vector<BufferSlot> outputs() const override {
    return {{Slots::hdr, 3}, {Slots::variance, 1, BufferKind::Variance}};
  }
  void execute(FrameContext& ctx) override;
  // Every integrator on the GPU, with the CPU's Sobol samples (the shutter's moving camera and
  // objects included); diffuse-gi's light grid built on the host; under MPI each rank traces
  // its stripes of rows on its own device.
  bool hasGpu() const override;
  void executeGpu(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override;
  void resetHistory() override { sums_.clear(); }
  // Splits the samples over `cluster`'s processes (MPI: every rank renders its rows, the image
  // is the same); null: this process alone.
  void distribute(SampleCluster* cluster) { cluster_ = cluster; }

 protected:
  const ParamTable<PTReferenceSettings>& tableFor() const override;

 private:
  // The frame's views rendered by renderView into sums_ (settings, seeds, accumulation and the
  // outputs as on either device).
  void render(FrameContext& ctx,
              const std::function<ReferenceResult(const View&, const ReferenceSettings&,
                                                  SampleSums&)>& renderView);
  std::vector<SampleSums> sums_;  // per view, carried across frames in accumulate mode
  uint64_t geometryVersion_ = ~0ull;
  SampleCluster* cluster_ = nullptr;
};

}  // namespace tandem
