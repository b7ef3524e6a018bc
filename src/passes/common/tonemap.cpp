#include "passes/common/tonemap.h"

#include "core/color.h"
#include "core/parallel.h"
#include "pipeline/frame_context.h"

namespace tandem {

const ParamTable<TonemapSettings>& TonemapPass::tableFor() const {
  using S = TonemapSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::exposure,
               {.name = "exposure", .min = -20, .max = 20, .doc = "exposure in stops (scale 2^EV)"})
          .add(&S::op,
               {.name = "operator", .doc = "tone curve", .choices = {"clamp", "reinhard", "aces"}});
  return table;
}

void TonemapPass::execute(FrameContext& ctx) {
  const Buffer& hdr = ctx.input(*this, Slots::hdr);
  Buffer& out = ctx.output(*this, Slots::output);
  const float ev = settings().exposure;
  const auto op = settings().op;
  parallelTiles(ctx.width, ctx.height, [&](int x0, int y0, int x1, int y1) {
    for (int y = y0; y < y1; ++y) {
      const size_t i = (size_t(y) * size_t(ctx.width) + size_t(x0)) * 3;
      tonemapSpan(hdr.data.data() + i, out.data.data() + i, size_t(x1 - x0) * 3, ev, op);
    }
  });
}

}  // namespace tandem
