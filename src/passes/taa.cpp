#include "passes/taa.h"

#include <cmath>

#include "core/image_filters.h"
#include "pipeline/frame_context.h"
#include "pipeline/view_tiles.h"

namespace tandem {

namespace {
inline Vec3 toYCoCg(Vec3 c) {
  return {0.25f * c.x + 0.5f * c.y + 0.25f * c.z, 0.5f * c.x - 0.5f * c.z,
          -0.25f * c.x + 0.5f * c.y - 0.25f * c.z};
}
inline Vec3 fromYCoCg(Vec3 y) {
  return {y.x + y.y - y.z, y.x + y.z, y.x - y.y - y.z};
}
}  // namespace

std::vector<BufferSlot> TAAPass::inputs() const {
  BufferSlot history{"taa", 3};
  history.history = true;
  return {{"hdr", 3}, {"motion", 2, BufferKind::Motion}, history};
}

std::vector<ParamDesc> TAAPass::params() const {
  return {{"alpha", ParamType::Float, 0.1, 0.01, 1, "weight of the current frame", {}},
          {"jitter_phases",
           ParamType::Int,
           8,
           1,
           256,
           "length of the Halton (2,3) jitter cycle",
           {}},
          {"clamp", ParamType::Bool, 1, 0, 1, "clamp history to the YCoCg neighbourhood box", {}},
          {"filter",
           ParamType::Enum,
           1,
           0,
           1,
           "history resampling",
           {"bilinear", "catmull_rom"}}};
}

void TAAPass::request(FrameRequest& r) const {
  r.jitter = true;
  r.jitterPhases = int(param("jitter_phases"));
}

void TAAPass::execute(FrameContext& ctx) {
  const Buffer& cur = ctx.input(*this, "hdr");
  const Buffer& motion = ctx.input(*this, "motion");
  const Buffer* prev = ctx.previous(*this, "taa");
  Buffer& out = ctx.output(*this, "taa");
  if (!prev || !prev->sameShape(out)) {
    out.data = cur.data;
    return;
  }
  const float alpha = float(param("alpha"));
  const bool clampHistory = param("clamp") != 0, catmullRom = param("filter") == 1;
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const Vec3 c = cur.rgb(x, y);
        const float* m = motion.at(x, y);
        const float px = float(x) + 0.5f - m[0], py = float(y) + 0.5f - m[1];
        if (px < float(v.x) || py < float(v.y) || px >= float(v.x + v.width()) ||
            py >= float(v.y + v.height())) {
          out.setRgb(x, y, c);  // came from outside the view: nothing to reuse
          continue;
        }
        float h[3];
        if (catmullRom)
          sampleCatmullRom(*prev, px, py, h);
        else
          sampleBilinear(*prev, px, py, h);
        Vec3 hist(std::max(h[0], 0.0f), std::max(h[1], 0.0f), std::max(h[2], 0.0f));
        if (clampHistory) {
          Vec3 lo(1e30f), hi(-1e30f);
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const int nx = std::clamp(x + dx, v.x, v.x + v.width() - 1);
              const int ny = std::clamp(y + dy, v.y, v.y + v.height() - 1);
              const Vec3 n = toYCoCg(cur.rgb(nx, ny));
              lo = vmin(lo, n);
              hi = vmax(hi, n);
            }
          hist = fromYCoCg(vmin(vmax(toYCoCg(hist), lo), hi));
        }
        // Luma-weighted blend (Karis): 1 / (1 + luma) tames fireflies.
        const float wc = alpha / (1.0f + toYCoCg(c).x);
        const float wh = (1.0f - alpha) / (1.0f + std::max(toYCoCg(hist).x, 0.0f));
        out.setRgb(x, y, (c * wc + hist * wh) * (1.0f / (wc + wh)));
      }
  });
}

}  // namespace tandem
