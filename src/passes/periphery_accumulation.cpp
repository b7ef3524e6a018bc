#include "passes/periphery_accumulation.h"

#include <algorithm>
#include <cmath>

#include "pipeline/frame_context.h"
#include "pipeline/view_tiles.h"

namespace tandem {

std::vector<BufferSlot> PeripheryAccumulationPass::inputs() const {
  BufferSlot history{"pt_history", 7, BufferKind::List};
  history.history = true;
  BufferSlot variance{"pt_variance", 1, BufferKind::Variance};
  variance.optional = true;
  return {{"pt_noisy", 3, BufferKind::Color},
          {"fov_mask", 1, BufferKind::Mask},
          {"fov_layer", 1, BufferKind::Id},
          {"motion", 2, BufferKind::Motion},
          {"position", 3, BufferKind::Position},
          {"depth", 1, BufferKind::Depth},
          variance,
          history};
}

std::vector<ParamDesc> PeripheryAccumulationPass::params() const {
  using T = ParamType;
  return {{"from_layer",
           T::Int,
           1,
           0,
           3,
           "first layer accumulated (0 inner, 1 middle, 2 outer; 3: none)",
           {}},
          {"alpha_min",
           T::Float,
           0.1,
           0.01,
           1,
           "smallest weight of this frame (the history's length)",
           {}},
          {"position_tolerance",
           T::Float,
           0.02,
           0.0001,
           1,
           "same surface: world distance over eye distance",
           {}}};
}

void PeripheryAccumulationPass::execute(FrameContext& ctx) {
  const Buffer& noisy = ctx.input(*this, "pt_noisy");
  const Buffer& mask = ctx.input(*this, "fov_mask");
  const Buffer& layer = ctx.input(*this, "fov_layer");
  const Buffer& motion = ctx.input(*this, "motion");
  const Buffer& position = ctx.input(*this, "position");
  const Buffer& depth = ctx.input(*this, "depth");
  const Buffer* prev = ctx.previous(*this, "pt_history");
  Buffer& accum = ctx.output(*this, "pt_accum");
  Buffer& accumVariance = ctx.output(*this, "pt_accum_variance");
  const Buffer* variance = ctx.optionalInput(*this, "pt_variance");
  Buffer& history = ctx.output(*this, "pt_history");
  const int fromLayer = int(param("from_layer"));
  const float alphaMin = float(param("alpha_min"));
  const float cap = 1.0f / alphaMin, tol = float(param("position_tolerance"));
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    const Vec3 eye = v.camera.desc.position;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        float* h = history.at(x, y);
        float* out = accum.at(x, y);
        if (mask.at(x, y)[0] <= 0.0f) {
          std::fill(h, h + 7, 0.0f);
          out[0] = out[1] = out[2] = 0.0f;
          accumVariance.at(x, y)[0] = -1.0f;
          continue;
        }
        const Vec3 c = noisy.rgb(x, y), p = position.rgb(x, y);
        Vec3 result = c;
        float n = 1;
        if (prev && int(layer.at(x, y)[0]) >= fromLayer && depth.at(x, y)[0] > 0) {
          const float* mv = motion.at(x, y);
          const int px = int(std::lround(float(x) - mv[0])),
                    py = int(std::lround(float(y) - mv[1]));
          if (v.contains(px, py)) {
            const float* ph = prev->at(px, py);
            const Vec3 pp(ph[4], ph[5], ph[6]);
            const float limit = tol * length(p - eye);
            if (ph[3] > 0 && length(pp - p) <= limit) {
              const float alpha = std::max(1.0f / (ph[3] + 1.0f), alphaMin);
              result = Vec3(ph[0], ph[1], ph[2]) * (1.0f - alpha) + c * alpha;
              n = std::min(ph[3] + 1.0f, cap);
            }
          }
        }
        out[0] = result.x, out[1] = result.y, out[2] = result.z;
        // The mean of n frames: this frame's variance over n (the young history's equal weights).
        const float v = variance ? variance->at(x, y)[0] : -1.0f;
        accumVariance.at(x, y)[0] = v >= 0.0f ? v / n : -1.0f;
        h[0] = result.x, h[1] = result.y, h[2] = result.z, h[3] = n;
        h[4] = p.x, h[5] = p.y, h[6] = p.z;
      }
  });
  // The mean history length (frames) over the accumulated layers' listed pixels.
  double frames = 0, count = 0;
  for (int y = 0; y < ctx.height; ++y)
    for (int x = 0; x < ctx.width; ++x)
      if (history.at(x, y)[3] > 0 && int(layer.at(x, y)[0]) >= fromLayer) {
        frames += history.at(x, y)[3];
        ++count;
      }
  ctx.counters["periphery_accumulation/mean_frames"] = count > 0 ? frames / count : 0.0;
}

}  // namespace tandem
