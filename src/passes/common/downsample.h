// downsample: a colour buffer at 1/2 or 1/4 of the frame (box or bilinear), the low-resolution
// input of reduced-extent passes (gather DoF at 1/2 resolution, mip-based blurs).
// Input: hdr. Output: half (1/2 extent) or quarter (1/4 extent). Parameter: filter.
#pragma once
#include "pipeline/param_table.h"

namespace tandem {

struct DownsampleSettings {
  enum class Filter { Box, Bilinear };
  Filter filter = Filter::Box;
};

class DownsamplePass : public SettingsPass<DownsampleSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* half = "half";
    static constexpr const char* hdr = "hdr";
    static constexpr const char* quarter = "quarter";
  };
  std::string type() const override { return "downsample"; }
  std::string description() const override {
    return "Colour at 1/2 and 1/4 resolution (box or bilinear)";
  }
  std::vector<BufferSlot> inputs() const override { return {{Slots::hdr, 3}}; }
  std::vector<BufferSlot> outputs() const override {
    return {{Slots::half, 3, BufferKind::Color, Extent::half()},
            {Slots::quarter, 3, BufferKind::Color, Extent::quarter()}};
  }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/downsample.comp
  void executeGpu(FrameContext& ctx) override;

 protected:
  const ParamTable<DownsampleSettings>& tableFor() const override;
};

}  // namespace tandem
