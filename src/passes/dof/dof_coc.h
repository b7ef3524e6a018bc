// dof_coc: the circle of confusion of every pixel from the camera's thin lens (Tan et al. 2022 eq.
// 6, scene/thin_lens.h): signed diameter in pixels, < 0 in the near field (in front of the focus
// plane), > 0 in the far field; the sky takes the far-field limit. |CoC| < max_coc (√2: one
// sensor cell) is the zone of focus, where the composite keeps the sharp raster colour.
// Input: position (world, from the G-buffer), depth (0 = sky). Output: coc (1 channel, signed).
#pragma once
#include "pipeline/pass.h"

namespace tandem {

class DofCocPass : public Pass {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* coc = "coc";
    static constexpr const char* depth = "depth";
    static constexpr const char* position = "position";
  };
  std::string type() const override { return "dof_coc"; }
  std::string description() const override {
    return "Circle of confusion from the thin lens (Tan et al. 2022 eq. 6), near < 0 < far";
  }
  std::vector<BufferSlot> inputs() const override {
    return {{Slots::position, 3, BufferKind::Position}, {Slots::depth, 1, BufferKind::Depth}};
  }
  std::vector<BufferSlot> outputs() const override { return {{Slots::coc, 1, BufferKind::Signed}}; }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/dof_coc.comp
  void executeGpu(FrameContext& ctx) override;
};

}  // namespace tandem
