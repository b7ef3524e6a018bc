#include "passes/interleaved/mb_composite.h"

#include <algorithm>

#include "core/parallel.h"
#include "pipeline/frame_context.h"

namespace tandem {

void MotionBlurCompositePass::execute(FrameContext& ctx) {
  const Buffer& post = ctx.input(*this, Slots::mbPostfx);
  const Buffer& il = ctx.input(*this, Slots::mbInterleaved);
  const Buffer& mask = ctx.input(*this, Slots::mbMask);
  Buffer& out = ctx.output(*this, Slots::hdr);
  parallelTiles(ctx.width, ctx.height, [&](int x0, int y0, int x1, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const float m = std::clamp(mask.at(x, y)[0], 0.0f, 1.0f);
        out.setRgb(x, y, post.rgb(x, y) * (1.0f - m) + il.rgb(x, y) * m);
      }
  });
}

}  // namespace tandem
