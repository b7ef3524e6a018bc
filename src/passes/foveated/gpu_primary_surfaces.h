// What the foveated passes' kernels read of a frame (shaders/foveated_args.h): the views (eyes)
// with their cameras, and the device addresses of the G-buffer's primary surfaces
// (PrimarySurfaces' slots, which the pass declares).
#pragma once
#include "gpu/shaders/foveated_args.h"
#include "pipeline/frame_context.h"
#include "pipeline/pass.h"

namespace tandem {

// The frame's views in this batch's constants (FoveatedView[ctx.views.size()]); their address.
uint64_t gpuFoveatedViews(FrameContext& ctx);
// The frame's views as rectangles and eyes (EyeView[ctx.views.size()]) in this batch's constants.
uint64_t gpuEyeViews(FrameContext& ctx);
GpuPrimarySurfaces gpuPrimarySurfaces(const FrameContext& ctx, const Pass& pass);

}  // namespace tandem
