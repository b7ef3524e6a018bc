#include "passes/baselines/taa.h"

#include <cmath>

#include "core/image_filters.h"
#include "gpu/shaders/taa_args.h"
#include "gpu/shaders/taa_spv.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"
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
  BufferSlot history{Slots::taa, 3};
  history.history = true;
  return {{Slots::hdr, 3}, {Slots::motion, 2, BufferKind::Motion}, history};
}

const ParamTable<TAASettings>& TAAPass::tableFor() const {
  using S = TAASettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::alpha,
               {.name = "alpha", .min = 0.01, .max = 1, .doc = "weight of the current frame"})
          .add(&S::jitterPhases, {.name = "jitter_phases",
                                  .min = 1,
                                  .max = 256,
                                  .doc = "length of the Halton (2,3) jitter cycle"})
          .add(&S::motionAlpha, {.name = "motion_alpha",
                                 .min = 0.01,
                                 .max = 1,
                                 .doc = "weight of the current frame for pixels moving "
                                        "motion_pixels or more per frame"})
          .add(&S::motionPixels,
               {.name = "motion_pixels",
                .min = 0.1,
                .max = 1000,
                .doc = "speed (pixels per frame) at which the weight reaches motion_alpha"})
          .add(&S::clamp, {.name = "clamp", .doc = "clamp history to the YCoCg neighbourhood box"})
          .add(&S::filter, {.name = "filter",
                            .doc = "history resampling",
                            .choices = {"bilinear", "catmull_rom"}})
          .add(&S::converge, {.name = "converge",
                              .doc = "average the first frames after a reset equally (weight 1/n "
                                     "until it falls to alpha)"});
  return table;
}

void TAAPass::request(FrameRequest& r) const {
  r.jitter = true;
  r.jitterPhases = settings().jitterPhases;
}

void TAAPass::execute(FrameContext& ctx) {
  const Buffer& cur = ctx.input(*this, Slots::hdr);
  const Buffer& motion = ctx.input(*this, Slots::motion);
  const Buffer* prev = ctx.previous(*this, Slots::taa);
  Buffer& out = ctx.output(*this, Slots::taa);
  if (!prev || !prev->sameShape(out)) {
    out.data = cur.data;
    framesAveraged_ = 1;
    return;
  }
  ++framesAveraged_;
  const TAASettings& s = settings();
  const float converging = s.converge ? 1.0f / float(framesAveraged_) : 0.0f;
  const float alpha = std::max(s.alpha, converging);
  const float motionAlpha = std::max(s.motionAlpha, converging);
  const float invMotionPixels = 1.0f / s.motionPixels;
  const bool clampHistory = s.clamp, catmullRom = s.filter == TAASettings::Filter::CatmullRom;
  constexpr int kTile = 32, kPad = kTile + 2;
  // One tile of at most kTile x kTile pixels (the scheduler may hand out larger ranges).
  auto tile = [&](const View& v, int x0, int y0, int x1, int y1) {
    // The tile and a 1-pixel border (clamped to the view) in YCoCg, then the 3-wide minimum
    // and maximum along rows: the 3x3 box of a pixel is three rows of those.
    float ycc[kPad][kPad][3], rowLo[kPad][kTile][3], rowHi[kPad][kTile][3];
    const int w = x1 - x0, h = y1 - y0;
    const int vx1 = v.x + v.width() - 1, vy1 = v.y + v.height() - 1;
    if (clampHistory) {
      for (int j = 0; j < h + 2; ++j) {
        const int sy = std::clamp(y0 + j - 1, v.y, vy1);
        for (int i = 0; i < w + 2; ++i) {
          const Vec3 c = toYCoCg(cur.rgb(std::clamp(x0 + i - 1, v.x, vx1), sy));
          ycc[j][i][0] = c.x;
          ycc[j][i][1] = c.y;
          ycc[j][i][2] = c.z;
        }
        for (int i = 0; i < w; ++i)
          for (int k = 0; k < 3; ++k) {
            const float a = ycc[j][i][k], b = ycc[j][i + 1][k], c = ycc[j][i + 2][k];
            rowLo[j][i][k] = std::min(a, std::min(b, c));
            rowHi[j][i][k] = std::max(a, std::max(b, c));
          }
      }
    }
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
        float hs[3];
        if (catmullRom) {
          if (!sampleCatmullRomRgbInside(*prev, px, py, hs)) sampleCatmullRom(*prev, px, py, hs);
        } else {
          sampleBilinear(*prev, px, py, hs);
        }
        Vec3 hist(std::max(hs[0], 0.0f), std::max(hs[1], 0.0f), std::max(hs[2], 0.0f));
        if (clampHistory) {
          const int i = x - x0, j = y - y0;  // rows j .. j + 2 of the padded tile
          Vec3 lo, hi;
          for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(rowLo[j][i][k], std::min(rowLo[j + 1][i][k], rowLo[j + 2][i][k]));
            hi[k] = std::max(rowHi[j][i][k], std::max(rowHi[j + 1][i][k], rowHi[j + 2][i][k]));
          }
          hist = fromYCoCg(vmin(vmax(toYCoCg(hist), lo), hi));
        }
        // A moving pixel trusts its (resampled, so slightly blurred) history less.
        const float speed = std::sqrt(m[0] * m[0] + m[1] * m[1]) * invMotionPixels;
        const float a = alpha + (motionAlpha - alpha) * std::min(speed, 1.0f);
        // Luma-weighted blend (Karis): 1 / (1 + luma) tames fireflies.
        const float wc = a / (1.0f + std::max(toYCoCg(c).x, 0.0f));
        const float wh = (1.0f - a) / (1.0f + std::max(toYCoCg(hist).x, 0.0f));
        out.setRgb(x, y, (c * wc + hist * wh) * (1.0f / (wc + wh)));
      }
  };
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    for (int ty = y0; ty < y1; ty += kTile)
      for (int tx = x0; tx < x1; tx += kTile)
        tile(v, tx, ty, std::min(tx + kTile, x1), std::min(ty + kTile, y1));
  });
}

void TAAPass::executeGpu(FrameContext& ctx) {
  const Buffer* prev = ctx.previous(*this, Slots::taa);
  const Buffer& cur = ctx.input(*this, Slots::hdr);
  TaaArgs a{};
  a.current = ctx.deviceInput(*this, Slots::hdr);
  a.motion = ctx.deviceInput(*this, Slots::motion);
  a.result = ctx.deviceOutput(*this, Slots::taa);
  // As execute(): no usable history, the current frame as is (the kernel copies it).
  if (prev && prev->sameShape(cur)) {
    a.history = ctx.devicePrevious(*this, Slots::taa);
    ++framesAveraged_;
  } else {
    framesAveraged_ = 1;
  }
  const TAASettings& s = settings();
  const float converging = s.converge ? 1.0f / float(framesAveraged_) : 0.0f;
  a.width = uint32_t(ctx.width);
  a.height = uint32_t(ctx.height);
  a.viewWidth = uint32_t(ctx.views.front().width());
  a.viewHeight = uint32_t(ctx.views.front().height());
  a.alpha = std::max(s.alpha, converging);
  a.motionAlpha = std::max(s.motionAlpha, converging);
  a.invMotionPixels = 1.0f / s.motionPixels;
  a.clampHistory = s.clamp ? 1 : 0;
  a.catmullRom = s.filter == TAASettings::Filter::CatmullRom ? 1 : 0;
  GpuFrame& gpu = *ctx.gpu;
  const GpuKernel& k = gpu.kernel("taa", kTaaSpv, sizeof(kTaaSpv) / 4, sizeof a);
  gpu.commands().dispatch(k, (a.width + 7) / 8, (a.height + 7) / 8, 1, &a);
}

}  // namespace tandem
