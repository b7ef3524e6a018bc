#include "passes/foveated/periphery_accumulation.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "passes/foveated/demodulation.h"
#include "pipeline/frame_context.h"
#include "pipeline/view_tiles.h"
#include "shading/gbuffer_layout.h"

namespace tandem {

namespace {
using H = HistoryChannels;
Vec3 vec3At(const float* px, int c) {
  return Vec3(px[c], px[c + 1], px[c + 2]);
}
void setVec3At(float* px, int c, Vec3 v) {
  px[c] = v.x, px[c + 1] = v.y, px[c + 2] = v.z;
}
}  // namespace

std::vector<BufferSlot> PeripheryAccumulationPass::inputs() const {
  BufferSlot history = HistoryChannels::slot();
  history.history = true;
  BufferSlot variance{Slots::ptVariance, 1, BufferKind::Variance};
  variance.optional = true;
  return {{Slots::ptNoisy, 3, BufferKind::Color},
          {Slots::fovMask, 1, BufferKind::Mask},
          {Slots::fovLayer, 1, BufferKind::Id},
          {Slots::motion, 2, BufferKind::Motion},
          {Slots::position, 3, BufferKind::Position},
          {Slots::normal, 3, BufferKind::Normal},
          {Slots::depth, 1, BufferKind::Depth},
          gbufferSlot(Slots::diffuse),
          {Slots::emission, 3, BufferKind::Color},
          variance,
          history};
}

const ParamTable<PeripheryAccumulationSettings>& PeripheryAccumulationPass::tableFor() const {
  using S = PeripheryAccumulationSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::fromLayer,
               {.name = "from_layer",
                .min = 0,
                .max = 3,
                .doc = "first layer accumulated (0 inner, 1 middle, 2 outer; 3: none)"})
          .add(&S::alphaMin, {.name = "alpha_min",
                              .min = 0.01,
                              .max = 1,
                              .doc = "smallest weight of this frame (the history's length)"})
          .add(&S::positionTolerance, {.name = "position_tolerance",
                                       .min = 0.0001,
                                       .max = 1,
                                       .doc = "same surface: world distance over eye distance"})
          .add(&S::normalTolerance,
               {.name = "normal_tolerance",
                .min = 0,
                .max = 180,
                .doc = "same surface: largest angle (degrees) between the normals"})
          .add(&S::demodulate,
               {.name = "demodulate",
                .doc =
                    "accumulate illumination (divided by the diffuse albedo): texture never lags"})
          .add(
              &S::fillUnlisted,
              {.name = "fill_unlisted",
               .doc = "unlisted pixels take their reprojected history (pt_accum_mask marks them)"});
  return table;
}

std::vector<CounterDesc> PeripheryAccumulationPass::counters() const {
  return {
      {PeripheryAccumulationCounters::meanFrames, "mean frames accumulated per pixel with history"},
  };
}

void PeripheryAccumulationPass::execute(FrameContext& ctx) {
  const Buffer& noisy = ctx.input(*this, Slots::ptNoisy);
  const Buffer& mask = ctx.input(*this, Slots::fovMask);
  const Buffer& layer = ctx.input(*this, Slots::fovLayer);
  const Buffer& motion = ctx.input(*this, Slots::motion);
  const Buffer& position = ctx.input(*this, Slots::position);
  const Buffer& depth = ctx.input(*this, Slots::depth);
  const Buffer& normal = ctx.input(*this, Slots::normal);
  const Buffer* prev = ctx.previous(*this, Slots::ptHistory);
  Buffer& accum = ctx.output(*this, Slots::ptAccum);
  Buffer& accumVariance = ctx.output(*this, Slots::ptAccumVariance);
  const Buffer* variance = ctx.optionalInput(*this, Slots::ptVariance);
  Buffer& history = ctx.output(*this, Slots::ptHistory);
  const PeripheryAccumulationSettings& s = settings();
  const int fromLayer = s.fromLayer;
  const float alphaMin = s.alphaMin;
  const float cap = 1.0f / alphaMin, tol = s.positionTolerance;
  const float minCos = std::cos(s.normalTolerance * kPi / 180.0f);
  Buffer& accumMask = ctx.output(*this, Slots::ptAccumMask);
  const bool fill = s.fillUnlisted;
  const Demodulation dm{ctx.input(*this, Slots::diffuse), ctx.input(*this, Slots::emission), depth,
                        s.demodulate};
  // The mean history length (frames) over the accumulated layers' pixels with an estimate.
  std::atomic<double> historyFrames = 0, historyPixels = 0;
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    const Vec3 eye = v.camera.desc.position;
    double tileFrames = 0, tilePixels = 0;
    // Where pixel (x, y) was last frame, read bilinearly from those of the four history pixels
    // around it that saw the same surface (position and normal): rgb and frames averaged; false
    // when they cover under a quarter of the footprint. Nearest-pixel reads would round a slow
    // motion (< 1/2 px per frame) away every frame and let the history lag behind; the normal
    // keeps a lit face from bleeding into a shaded one across a crease, which positions within
    // the tolerance would allow.
    // out: illumination rgb and frames, in pt_history's order from kIllumination.
    static_assert(H::kFrames == H::kIllumination + 3);
    constexpr int kOutFrames = H::kFrames - H::kIllumination;
    auto reproject = [&](int x, int y, Vec3 p, Vec3 nrm, float out[4]) {
      const float* mv = motion.at(x, y);
      const float bx = float(x) - mv[0], by = float(y) - mv[1];  // in pixel indices
      const int ix = int(std::floor(bx)), iy = int(std::floor(by));
      const float tx = bx - float(ix), ty = by - float(iy);
      const float limit = tol * length(p - eye);
      float wsum = 0;
      std::fill(out, out + 4, 0.0f);
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
          const float w = (i ? tx : 1.0f - tx) * (j ? ty : 1.0f - ty);
          if (w <= 0.0f || !v.contains(ix + i, iy + j)) continue;
          const float* ph = prev->at(ix + i, iy + j);
          if (ph[H::kFrames] <= 0 || length(vec3At(ph, H::kPosition) - p) > limit ||
              dot(vec3At(ph, H::kNormal), nrm) < minCos)
            continue;
          // Illumination and frames: the four channels from kIllumination.
          for (int k = 0; k < 4; ++k) out[k] += w * ph[H::kIllumination + k];
          wsum += w;
        }
      if (wsum < 0.25f) return false;
      for (int k = 0; k < 4; ++k) out[k] /= wsum;
      return true;
    };
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        float* h = history.at(x, y);
        float* out = accum.at(x, y);
        const bool listed = mask.at(x, y)[0] > 0.0f;
        const bool accumulated =
            prev && int(layer.at(x, y)[0]) >= fromLayer && depth.at(x, y)[0] > 0;
        const Vec3 p = position.rgb(x, y), nrm = normal.rgb(x, y);
        float hist[4] = {0, 0, 0, 0};
        const bool reprojected = accumulated && (listed || fill) && reproject(x, y, p, nrm, hist);
        if (!listed && !reprojected) {
          std::fill(h, h + H::kCount, 0.0f);
          out[0] = out[1] = out[2] = 0.0f;
          accumVariance.at(x, y)[0] = -1.0f;
          accumMask.at(x, y)[0] = 0.0f;
          continue;
        }
        // In illumination units (texture is this frame's): this frame's sample where listed,
        // else the history alone (an unlisted pixel keeps what the surface had).
        Vec3 result = Vec3(hist[0], hist[1], hist[2]);
        float n = hist[kOutFrames];
        if (listed) {
          const Vec3 c = noisy.rgb(x, y);
          result = Vec3(dm.illumination(c.x, x, y, 0), dm.illumination(c.y, x, y, 1),
                        dm.illumination(c.z, x, y, 2));
          n = 1.0f;
        }
        if (listed && reprojected) {
          const float alpha = std::max(1.0f / (hist[kOutFrames] + 1.0f), alphaMin);
          result = Vec3(hist[0], hist[1], hist[2]) * (1.0f - alpha) + result * alpha;
          n = std::min(hist[kOutFrames] + 1.0f, cap);
        }
        for (int k = 0; k < 3; ++k) out[k] = dm.colour(result[k], x, y, k);
        accumMask.at(x, y)[0] = 1.0f;
        // The mean of n frames: this frame's variance over n (the young history's equal weights).
        const float var = variance && listed ? variance->at(x, y)[0] : -1.0f;
        accumVariance.at(x, y)[0] = var >= 0.0f ? var / n : -1.0f;
        setVec3At(h, H::kIllumination, result);
        h[H::kFrames] = n;
        setVec3At(h, H::kPosition, p);
        setVec3At(h, H::kNormal, nrm);
        if (int(layer.at(x, y)[0]) >= fromLayer) tileFrames += n, tilePixels += 1;
      }
    historyFrames += tileFrames;
    historyPixels += tilePixels;
  });
  const double count = historyPixels.load();
  ctx.report(*this, PeripheryAccumulationCounters::meanFrames,
             count > 0 ? historyFrames.load() / count : 0.0);
}

}  // namespace tandem
