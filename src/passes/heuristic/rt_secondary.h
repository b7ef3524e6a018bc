// rt_secondary: Walewski et al. 2019 §3.3 (Listing 8a) for the pixels of the heuristic mask,
// starting from the G-buffer (no primary rays): shadows of every light (Listing 8b; classified by
// the frame's shadow maps where they are certain, shadow rays the rest: `shadows`), reflection and
// refraction rays with recursion (Listing 8c, rt/whitted.h). Outside the mask all three are 0
// (Listing 8a; Figure 5's buffers), or the shadow 1 with outside_mask_shadow = 1. Inputs: G-buffer
// sample targets, heuristic_mask, rt_request (optional record: time each object and effect; a
// deadline), heuristic_order (optional: the nodes' ranks, the order tiles are traced in under a
// deadline). Outputs: shadow, reflection, refraction, traced_mask (the heuristic mask where it was
// traced: all of it, unless the deadline cut the tail), shadow_class (when read: traced, lit,
// shadowed shares of each pixel's lights), rt_stats (what it traced, for the next frame's
// heuristic). Parameters: the Whitted settings, shadow_class_light, outside_mask_shadow.
#pragma once
#include "passes/common/whitted_settings.h"
#include "rt/whitted.h"

namespace tandem {

struct RTSecondarySettings {
  WhittedParams whitted{};
  int shadowClassLight = -1;
  float outsideMaskShadow = 0;
};

// The counters RTSecondaryPass reports each frame (Pass::counters, FrameContext::report).
struct RTSecondaryCounters {
  static constexpr const char* itemsCut = "rt_secondary/items_cut";
};

class RTSecondaryPass : public SettingsPass<RTSecondarySettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* geoNormal = "geo_normal";
    static constexpr const char* heuristicMask = "heuristic_mask";
    static constexpr const char* heuristicOrder = "heuristic_order";
    static constexpr const char* objectId = "object_id";
    static constexpr const char* reflection = "reflection";
    static constexpr const char* refraction = "refraction";
    static constexpr const char* rtRequest = "rt_request";
    static constexpr const char* rtStats = "rt_stats";
    static constexpr const char* shadow = "shadow";
    static constexpr const char* shadowClass = "shadow_class";
    static constexpr const char* traced = "traced";
    static constexpr const char* tracedMask = "traced_mask";
  };
  std::string type() const override { return "rt_secondary"; }
  std::string description() const override {
    return "Ray-traced shadows, reflections, refractions for masked pixels (Walewski et al. 2019 "
           "§3.3)";
  }
  std::vector<BufferSlot> inputs() const override;
  std::vector<BufferSlot> outputs() const override;
  void execute(FrameContext& ctx) override;
  // On the GPU every masked pixel is traced: a deadline (rt_request) cuts nothing there, and
  // rt_stats' times are the pass's GPU time shared by each object's rays.
  bool hasGpu() const override { return true; }  // shaders/rt_secondary.comp
  void executeGpu(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override;
  void resetHistory() override { tailMs_ = 0; }

 protected:
  const ParamTable<RTSecondarySettings>& tableFor() const override;

 private:
  double tailMs_ = 0;  // deadline mode: smoothed time from the deadline to the pass's end
};

}  // namespace tandem
