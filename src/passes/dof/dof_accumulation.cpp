#include "passes/dof/dof_accumulation.h"

#include <cmath>

#include "core/image_filters.h"
#include "core/parallel.h"
#include "passes/dof/dof_common.h"
#include "pipeline/frame_context.h"

namespace tandem {

std::vector<BufferSlot> DofAccumulationPass::inputs() const {
  std::vector<BufferSlot> in = {
      {"rt_near", dof::kLayerChannels, BufferKind::Color, Extent::any()},
      {"rt_far", dof::kLayerChannels, BufferKind::Color, Extent::any()},
      {"rt_hit", dof::kHitChannels, BufferKind::Mask, Extent::any()},
      {"rt_far_position", dof::kFarPositionChannels, BufferKind::Position, Extent::any()},
      {"motion", 2, BufferKind::Motion}};
  for (const char* h : {"acc_near", "acc_far"}) {
    BufferSlot s{h, 5, BufferKind::Color, Extent::any()};
    s.history = true;
    in.push_back(s);
  }
  BufferSlot moments{"acc_moments", 3, BufferKind::List, Extent::any()};
  moments.history = true;
  in.push_back(moments);
  return in;
}

std::vector<BufferSlot> DofAccumulationPass::outputs() const {
  return {{"acc_near", 5, BufferKind::Color, Extent::any()},
          {"acc_far", 5, BufferKind::Color, Extent::any()},
          {"acc_moments", 3, BufferKind::List, Extent::any()},
          {"rt_color", dof::RtChannels::kCount, BufferKind::Color, Extent::any()},
          {"dof_variance", 1, BufferKind::Variance, Extent::any()}};
}

const ParamTable<DofAccumulationSettings>& DofAccumulationPass::tableFor() const {
  using S = DofAccumulationSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::historyWeight,
               {.name = "history_weight",
                .min = 0,
                .max = 0.999,
                .doc = "exponential moving average: weight of the history (the paper: 0.95)"})
          .add(&S::motionPixels,
               {.name = "motion_pixels",
                .min = 0,
                .max = 1000,
                .doc = "a pixel moving this many frame pixels uses this frame's hit ratio"})
          .add(&S::adaptiveAlpha,
               {.name = "adaptive_alpha",
                .doc = "per-pixel blend factor from the temporal gradient (Schied 2018; beyond the "
                       "paper)"})
          .add(&S::varianceBlur, {.name = "variance_blur",
                                  .min = 0,
                                  .max = 16,
                                  .doc = "σ of the variance's Gaussian blur"});
  return table;
}

namespace {

// Bilinear history sample (5 or 3 channels); false outside the buffer.
bool history(const Buffer* b, float x, float y, float* out) {
  if (!b || x < 0 || y < 0 || x > float(b->width) || y > float(b->height)) return false;
  sampleBilinear(*b, x, y, out);
  return true;
}

// Where the far field of mask pixel (x, y) was last frame: its rays' mean far hit (else its 3x3
// neighbourhood's) seen by the previous camera; (fxp, fyp) unchanged when there is none.
void reprojectFar(const Buffer& farPosIn, int x, int y, const View& view, float scale, float& fxp,
                  float& fyp) {
  const int w = farPosIn.width, h = farPosIn.height;
  Vec3 farP(0.0f);
  float farW = 0.0f;
  if (farPosIn.at(x, y)[dof::kFarPositionValid] > 0) {
    const float* p = farPosIn.at(x, y);
    farP = Vec3(p[0], p[1], p[2]);
    farW = 1.0f;
  } else {
    for (int j = std::max(y - 1, 0); j <= std::min(y + 1, h - 1); ++j)
      for (int i = std::max(x - 1, 0); i <= std::min(x + 1, w - 1); ++i) {
        const float* p = farPosIn.at(i, j);
        if (p[dof::kFarPositionValid] > 0) farP = farP + Vec3(p[0], p[1], p[2]), farW += 1.0f;
      }
    if (farW > 0) farP = farP * (1.0f / farW);
  }
  Vec2 prevPixel;
  if (farW > 0 && view.prevCamera.project(farP, prevPixel)) {
    fxp = (prevPixel.x + float(view.x)) / scale;  // the view's pixel -> the frame's
    fyp = (prevPixel.y + float(view.y)) / scale;
  }
}

// Temporal gradient: the change of luminance beyond two standard deviations of the samples'
// noise, relative to the brighter of the two, raises the current weight.
float adaptiveAlpha(float alpha, float lum, const float* hn, const float* hf, const float* hm) {
  const float hsum = hn[3] + hf[3];
  const float histLum =
      hsum > 0 ? luminance(Vec3(hn[0] + hf[0], hn[1] + hf[1], hn[2] + hf[2])) / hsum : lum;
  const float sigma = std::sqrt(std::max(hm[1] - hm[0] * hm[0], 0.0f));
  const float lambda =
      dof::saturate((std::abs(lum - histLum) - 2.0f * sigma) / std::max({lum, histLum, 1e-3f}));
  return alpha + (1.0f - alpha) * lambda;
}

}  // namespace

void DofAccumulationPass::execute(FrameContext& ctx) {
  const Buffer& nearIn = ctx.input(*this, "rt_near");
  const Buffer& farIn = ctx.input(*this, "rt_far");
  const Buffer& hitIn = ctx.input(*this, "rt_hit");
  const Buffer& farPosIn = ctx.input(*this, "rt_far_position");
  const Buffer& motion = ctx.input(*this, "motion");
  const int w = nearIn.width, h = nearIn.height;
  const Buffer* prevNear = ctx.previous(*this, "acc_near");
  const Buffer* prevFar = ctx.previous(*this, "acc_far");
  const Buffer* prevMoments = ctx.previous(*this, "acc_moments");
  auto fits = [&](const Buffer* b) { return b && b->width == w && b->height == h; };
  if (!fits(prevNear) || !fits(prevFar) || !fits(prevMoments))
    prevNear = prevFar = prevMoments = nullptr;
  Buffer& accNear = ctx.output(*this, "acc_near", w, h);
  Buffer& accFar = ctx.output(*this, "acc_far", w, h);
  Buffer& accMoments = ctx.output(*this, "acc_moments", w, h);
  Buffer& color = ctx.output(*this, "rt_color", w, h);
  Buffer variance(w, h, 1, 0.0f, BufferKind::Variance);
  const float scale = float(ctx.width) / float(w);
  const float minAlpha = 1.0f - settings().historyWeight;
  const float motionPx = settings().motionPixels;
  const bool adaptive = settings().adaptiveAlpha;

  parallelRows(h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const float fx = (float(x) + 0.5f) * scale, fy = (float(y) + 0.5f) * scale;
      const View& view =
          viewAt(ctx.views, std::min(int(fx), ctx.width - 1), std::min(int(fy), ctx.height - 1));
      const float* mv =
          motion.at(std::min(int(fx), motion.width - 1), std::min(int(fy), motion.height - 1));
      const float nx = (fx - mv[0]) / scale, ny = (fy - mv[1]) / scale;  // near: motion vector
      // Far: the mean far-field hit of the pixel's rays, else of its 3x3 neighbourhood's.
      float fxp = nx, fyp = ny;
      reprojectFar(farPosIn, x, y, view, scale, fxp, fyp);
      float hn[5] = {}, hf[5] = {}, hm[3] = {};
      const bool haveNear = history(prevNear, nx, ny, hn) && history(prevMoments, nx, ny, hm);
      const bool haveFar = history(prevFar, fxp, fyp, hf);
      const bool haveHistory = haveNear && haveFar;

      const float rays = hitIn.at(x, y)[dof::kHitRays], hc = hitIn.at(x, y)[dof::kHitNearShare];
      const float* cn = nearIn.at(x, y);
      const float* cf = farIn.at(x, y);
      // This frame's merged sample (the mean of its rays).
      const float lum = luminance(lerp(Vec3(cf[0], cf[1], cf[2]), Vec3(cn[0], cn[1], cn[2]), hc));
      float age = haveHistory ? hm[2] : 0.0f;
      float alpha = rays > 0 ? std::max(minAlpha, 1.0f / (age + 1.0f)) : 0.0f;
      if (!haveHistory) {
        for (float& v : hn) v = 0.0f;
        for (float& v : hf) v = 0.0f;
        for (float& v : hm) v = 0.0f;
        age = 0.0f;
        alpha = rays > 0 ? 1.0f : 0.0f;
      } else if (adaptive && rays > 0) {
        alpha = adaptiveAlpha(alpha, lum, hn, hf, hm);
      }
      const float curNear[5] = {hc * cn[0], hc * cn[1], hc * cn[2], hc, hc * cn[dof::kLayerCoc]};
      const float hf1 = 1.0f - hc;
      const float curFar[5] = {hf1 * cf[0], hf1 * cf[1], hf1 * cf[2], hf1,
                               hf1 * cf[dof::kLayerCoc]};
      float* an = accNear.at(x, y);
      float* af = accFar.at(x, y);
      for (int c = 0; c < 5; ++c) {
        an[c] = hn[c] + (curNear[c] - hn[c]) * alpha;
        af[c] = hf[c] + (curFar[c] - hf[c]) * alpha;
      }

      // Merge: near and far normalised by their accumulated shares, then lerped by the hit
      // ratio (this frame's while the pixel moves).
      const float H = an[3], F = af[3], total = H + F;
      float* o = color.at(x, y);
      float* am = accMoments.at(x, y);
      am[2] = std::min(age + (rays > 0 ? 1.0f : 0.0f), 1000.0f);
      if (total <= 1e-6f) {
        for (int c = 0; c < dof::RtChannels::kCount; ++c) o[c] = 0.0f;
        am[0] = am[1] = 0.0f;
        continue;
      }
      const bool moving = view.cameraMoved || mv[0] * mv[0] + mv[1] * mv[1] > motionPx * motionPx;
      float hr = H / total;
      if (moving && rays > 0) hr = hc;
      const Vec3 nearC = H > 1e-6f ? Vec3(an[0], an[1], an[2]) * (1.0f / H) : Vec3(0.0f);
      const Vec3 farC = F > 1e-6f ? Vec3(af[0], af[1], af[2]) * (1.0f / F) : Vec3(0.0f);
      const float nearCoc = H > 1e-6f ? an[4] / H : 0.0f, farCoc = F > 1e-6f ? af[4] / F : 0.0f;
      if (H <= 1e-6f) hr = 0.0f;
      if (F <= 1e-6f) hr = 1.0f;
      const Vec3 c = lerp(farC, nearC, hr);
      o[0] = c.x, o[1] = c.y, o[2] = c.z;
      // Temporal moments of each frame's merged ray-traced luminance (Schied et al. 2017), and
      // from them the variance of the accumulated mean (the frames' variance over the number
      // the moving average effectively holds): large at new or changing content and at
      // unconverged bokeh, small where the accumulation has converged.
      if (rays > 0) {
        am[0] = hm[0] + (lum - hm[0]) * alpha;
        am[1] = hm[1] + (lum * lum - hm[1]) * alpha;
      } else {
        am[0] = hm[0], am[1] = hm[1];
      }
      const float frames = std::min(std::max(am[2], 1.0f), (2.0f - minAlpha) / minAlpha);
      variance.at(x, y)[0] = std::max(am[1] - am[0] * am[0], 0.0f) / frames;
      using C = dof::RtChannels;
      o[C::kCoc] = farCoc + (nearCoc - farCoc) * hr;
      o[C::kHit] = hr;
      o[C::kCoverage] = 1.0f;
      o[C::kNear] = nearC.x, o[C::kNear + 1] = nearC.y, o[C::kNear + 2] = nearC.z;
    }
  });
  double mean = 0, above = 0;
  for (float v : variance.data) mean += v, above += v > 1e-6f;
  const double n = double(std::max<size_t>(1, variance.data.size()));
  ctx.counters["dof_accumulation/mean_variance"] = mean / n;
  // Share of pixels whose variance alone adds a ray at m = 10 with the paper's weight 1e5.
  ctx.counters["dof_accumulation/variance_above_1e-6"] = above / n;
  Buffer& varOut = ctx.output(*this, "dof_variance", w, h);
  varOut.data = gaussianBlur(variance, settings().varianceBlur).data;
}

}  // namespace tandem
