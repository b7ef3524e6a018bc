#include "passes/common/tonemap.h"

#include "core/color.h"
#include "core/parallel.h"
#include "pipeline/frame_context.h"

namespace tandem {

std::vector<ParamDesc> TonemapPass::params() const {
  return {{"exposure", ParamType::Float, 0.0, -20.0, 20.0, "exposure in stops (scale 2^EV)", {}},
          {"operator", ParamType::Enum, 2, 0, 2, "tone curve", {"clamp", "reinhard", "aces"}}};
}

void TonemapPass::execute(FrameContext& ctx) {
  const Buffer& hdr = ctx.input(*this, "hdr");
  Buffer& out = ctx.output(*this, "output");
  const float ev = float(param("exposure"));
  const auto op = ToneOperator(int(param("operator")));
  parallelTiles(ctx.width, ctx.height, [&](int x0, int y0, int x1, int y1) {
    for (int y = y0; y < y1; ++y) {
      const size_t i = (size_t(y) * size_t(ctx.width) + size_t(x0)) * 3;
      tonemapSpan(hdr.data.data() + i, out.data.data() + i, size_t(x1 - x0) * 3, ev, op);
    }
  });
}

}  // namespace tandem
