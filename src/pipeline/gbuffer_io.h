// A pass's G-buffer slots as a writer (GBufferView) or a reader (GBufferReader): raster/ and
// shading/ take buffers, the frame context binds them to the pass's buffer names.
#pragma once
#include "pipeline/frame_context.h"
#include "pipeline/pass.h"
#include "raster/gbuffer.h"
#include "shading/gbuffer_sample.h"

namespace tandem {

// Depth and motion only when something reads them (FrameContext::keepAllOutputs).
inline GBufferView gbufferTargets(FrameContext& ctx, const Pass& pass) {
  return GBufferView::create([&](const BufferSlot& s) -> Buffer* {
    if (s.slot == "depth" || s.slot == "motion") return ctx.outputIfConsumed(pass, s.slot);
    return &ctx.output(pass, s.slot);
  });
}

inline GBufferReader gbufferSource(const FrameContext& ctx, const Pass& pass) {
  return GBufferReader(
      [&](const BufferSlot& s) -> const Buffer& { return ctx.input(pass, s.slot); });
}

}  // namespace tandem
