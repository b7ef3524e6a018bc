#include "passes/tonemap.h"

#include <cmath>

#include "core/color.h"
#include "core/parallel.h"
#include "pipeline/frame_context.h"

namespace tandem {

namespace {
float aces(float x) {
  const float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
  return std::clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0f, 1.0f);
}
}  // namespace

Vec3 tonemapPixel(Vec3 c, float ev, ToneOperator op) {
  c = c * std::exp2(ev);
  for (int k = 0; k < 3; ++k) {
    float v = std::isfinite(c[k]) ? std::max(c[k], 0.0f) : 0.0f;
    switch (op) {
      case ToneOperator::Clamp:
        v = std::min(v, 1.0f);
        break;
      case ToneOperator::Reinhard:
        v = v / (1.0f + v);
        break;
      case ToneOperator::Aces:
        v = aces(v);
        break;
    }
    c[k] = linearToSrgbFast(v);
  }
  return c;
}

std::vector<ParamDesc> TonemapPass::params() const {
  return {{"exposure", ParamType::Float, 0.0, -20.0, 20.0, "exposure in stops (scale 2^EV)", {}},
          {"operator", ParamType::Enum, 2, 0, 2, "tone curve", {"clamp", "reinhard", "aces"}}};
}

void TonemapPass::execute(FrameContext& ctx) {
  const Buffer& hdr = ctx.input(bufferName("hdr"));
  Buffer& out = ctx.output(bufferName("output"), 3);
  const float ev = float(param("exposure"));
  const auto op = ToneOperator(int(param("operator")));
  parallelTiles(ctx.width, ctx.height, [&](int x0, int y0, int x1, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) out.setRgb(x, y, tonemapPixel(hdr.rgb(x, y), ev, op));
  });
}

}  // namespace tandem
