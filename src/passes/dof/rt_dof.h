// rt_dof: ray-traced depth of field (Tan et al. 2022 §3.2.2, Cook et al. 1984) in the pixels of the
// ray mask, at the mask's resolution. Each of a pixel's x_f rays starts at a point of the aperture
// (disk or the camera's n-gon: Camera::lensPoint, the reference's lens) and goes through the
// pixel's point on the focus plane; the pixel position is jittered over the mask pixel's
// footprint and both come from the Sobol sampler, new every frame. Hits are shaded by the one
// shading function with ray-traced shadows, mirrors and glass (rt/whitted.h, as rt-only), rays
// traced in 8-wide packets. Each ray's colour and CoC are split into the near and far field by
// its hit's CoC (dof::nearShare: out-of-focus near field; sharp hits count as far); the hit ratio
// is the near share of the pixel's rays, and the mean far-field world position is kept for the far
// field's reprojection. Input: ray_mask. Outputs (the mask's size): rt_near and rt_far (rgb, mean
// |CoC| in frame pixels), rt_hit (hit ratio, rays), rt_far_position (mean far hit, 1 where there is
// one).
#pragma once
#include "passes/common/whitted_settings.h"
#include "passes/dof/dof_common.h"

namespace tandem {

struct RTDofSettings {
  WhittedParams whitted{};
  bool reuseRaster = false;
};

// The counters RTDofPass reports each frame (Pass::counters, FrameContext::report).
struct RTDofCounters {
  static constexpr const char* lensRays = "rt_dof/lens_rays";
  static constexpr const char* reusedShare = "rt_dof/reused_share";
};

class RTDofPass : public SettingsPass<RTDofSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* depth = "depth";
    static constexpr const char* hdr = "hdr";
    static constexpr const char* rayMask = "ray_mask";
    static constexpr const char* rtFar = "rt_far";
    static constexpr const char* rtFarPosition = "rt_far_position";
    static constexpr const char* rtHit = "rt_hit";
    static constexpr const char* rtNear = "rt_near";
  };
  std::string type() const override { return "rt_dof"; }
  std::string description() const override {
    return "Ray-traced DoF: lens rays in the ray mask, split into near and far fields (Tan et al. "
           "2022 "
           "§3.2.2)";
  }
  std::vector<BufferSlot> inputs() const override {
    BufferSlot sharp{Slots::hdr, 3}, depth{Slots::depth, 1, BufferKind::Depth};
    sharp.optional = depth.optional = true;  // reuse_raster only
    return {{Slots::rayMask, 1, BufferKind::Count, Extent::any()}, sharp, depth};
  }
  std::vector<BufferSlot> outputs() const override {
    return {dof::layerSlot(Slots::rtNear), dof::layerSlot(Slots::rtFar), dof::hitSlot(),
            dof::farPositionSlot()};
  }
  void execute(FrameContext& ctx) override;
  bool hasGpu() const override { return true; }  // shaders/rt_dof.comp, rt_dof_gpu.cpp
  void executeGpu(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override;

 protected:
  const ParamTable<RTDofSettings>& tableFor() const override;
};

}  // namespace tandem
