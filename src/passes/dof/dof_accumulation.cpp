#include "passes/dof/dof_accumulation.h"

#include <cmath>

#include "core/image_filters.h"
#include "core/parallel.h"
#include "passes/dof/dof_common.h"
#include "pipeline/frame_context.h"

namespace tandem {

std::vector<BufferSlot> DofAccumulationPass::inputs() const {
  std::vector<BufferSlot> in = {dof::layerSlot(Slots::rtNear),
                                dof::layerSlot(Slots::rtFar),
                                dof::hitSlot(),
                                dof::farPositionSlot(),
                                {Slots::motion, 2, BufferKind::Motion}};
  for (BufferSlot s : {dof::AccChannels::slot(Slots::accNear),
                       dof::AccChannels::slot(Slots::accFar), dof::MomentChannels::slot()}) {
    s.history = true;
    in.push_back(s);
  }
  return in;
}

std::vector<BufferSlot> DofAccumulationPass::outputs() const {
  return {dof::AccChannels::slot(Slots::accNear),
          dof::AccChannels::slot(Slots::accFar),
          dof::MomentChannels::slot(),
          dof::RtChannels::slot(Slots::rtColor),
          {Slots::dofVariance, 1, BufferKind::Variance, Extent::any()}};
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
    farP = farPosIn.rgb(x, y);  // x, y, z
    farW = 1.0f;
  } else {
    for (int j = std::max(y - 1, 0); j <= std::min(y + 1, h - 1); ++j)
      for (int i = std::max(x - 1, 0); i <= std::min(x + 1, w - 1); ++i)
        if (farPosIn.at(i, j)[dof::kFarPositionValid] > 0)
          farP = farP + farPosIn.rgb(i, j), farW += 1.0f;
    if (farW > 0) farP = farP * (1.0f / farW);
  }
  Vec2 prevPixel;
  if (farW > 0 && view.prevCamera.project(farP, prevPixel)) {
    fxp = (prevPixel.x + float(view.x)) / scale;  // the view's pixel -> the frame's
    fyp = (prevPixel.y + float(view.y)) / scale;
  }
}

// A layer's sample (rt_near, rt_far: rgb then CoC) premultiplied by its share of the rays, in
// acc_near / acc_far's channels.
void premultiplied(const float* layer, float share, float* out) {
  using A = dof::AccChannels;
  for (int k = 0; k < 3; ++k) out[A::kRgb + k] = share * layer[k];
  out[A::kShare] = share;
  out[A::kCoc] = share * layer[dof::kLayerCoc];
}

// Temporal gradient: the change of luminance beyond two standard deviations of the samples'
// noise, relative to the brighter of the two, raises the current weight.
float adaptiveAlpha(float alpha, float lum, const float* hn, const float* hf, const float* hm) {
  using A = dof::AccChannels;
  using M = dof::MomentChannels;
  const float hsum = hn[A::kShare] + hf[A::kShare];
  const float histLum =
      hsum > 0 ? luminance(dof::rgbAt(hn, A::kRgb) + dof::rgbAt(hf, A::kRgb)) / hsum : lum;
  const float sigma = std::sqrt(std::max(hm[M::kMeanSquare] - hm[M::kMean] * hm[M::kMean], 0.0f));
  const float lambda =
      dof::saturate((std::abs(lum - histLum) - 2.0f * sigma) / std::max({lum, histLum, 1e-3f}));
  return alpha + (1.0f - alpha) * lambda;
}

}  // namespace

std::vector<CounterDesc> DofAccumulationPass::counters() const {
  return {
      {DofAccumulationCounters::meanVariance, "mean per-pixel variance of the accumulated image"},
      {DofAccumulationCounters::varianceAbove1e6, "share of pixels whose variance exceeds 1e-6"},
  };
}

void DofAccumulationPass::execute(FrameContext& ctx) {
  const Buffer& nearIn = ctx.input(*this, Slots::rtNear);
  const Buffer& farIn = ctx.input(*this, Slots::rtFar);
  const Buffer& hitIn = ctx.input(*this, Slots::rtHit);
  const Buffer& farPosIn = ctx.input(*this, Slots::rtFarPosition);
  const Buffer& motion = ctx.input(*this, Slots::motion);
  const int w = nearIn.width, h = nearIn.height;
  const Buffer* prevNear = ctx.previous(*this, Slots::accNear);
  const Buffer* prevFar = ctx.previous(*this, Slots::accFar);
  const Buffer* prevMoments = ctx.previous(*this, Slots::accMoments);
  auto fits = [&](const Buffer* b) { return b && b->width == w && b->height == h; };
  if (!fits(prevNear) || !fits(prevFar) || !fits(prevMoments))
    prevNear = prevFar = prevMoments = nullptr;
  Buffer& accNear = ctx.output(*this, Slots::accNear, w, h);
  Buffer& accFar = ctx.output(*this, Slots::accFar, w, h);
  Buffer& accMoments = ctx.output(*this, Slots::accMoments, w, h);
  Buffer& color = ctx.output(*this, Slots::rtColor, w, h);
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
      using A = dof::AccChannels;
      using M = dof::MomentChannels;
      float hn[A::kCount] = {}, hf[A::kCount] = {}, hm[M::kCount] = {};
      const bool haveNear = history(prevNear, nx, ny, hn) && history(prevMoments, nx, ny, hm);
      const bool haveFar = history(prevFar, fxp, fyp, hf);
      const bool haveHistory = haveNear && haveFar;

      const float rays = hitIn.at(x, y)[dof::kHitRays], hc = hitIn.at(x, y)[dof::kHitNearShare];
      const float* cn = nearIn.at(x, y);
      const float* cf = farIn.at(x, y);
      // This frame's merged sample (the mean of its rays).
      const float lum = luminance(lerp(dof::rgbAt(cf, 0), dof::rgbAt(cn, 0), hc));
      float age = haveHistory ? hm[M::kFrames] : 0.0f;
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
      float curNear[A::kCount], curFar[A::kCount];
      premultiplied(cn, hc, curNear);
      premultiplied(cf, 1.0f - hc, curFar);
      float* an = accNear.at(x, y);
      float* af = accFar.at(x, y);
      for (int c = 0; c < A::kCount; ++c) {
        an[c] = hn[c] + (curNear[c] - hn[c]) * alpha;
        af[c] = hf[c] + (curFar[c] - hf[c]) * alpha;
      }

      // Merge: near and far normalised by their accumulated shares, then lerped by the hit
      // ratio (this frame's while the pixel moves).
      const float H = an[A::kShare], F = af[A::kShare], total = H + F;
      float* o = color.at(x, y);
      float* am = accMoments.at(x, y);
      am[M::kFrames] = std::min(age + (rays > 0 ? 1.0f : 0.0f), 1000.0f);
      if (total <= 1e-6f) {
        for (int c = 0; c < dof::RtChannels::kCount; ++c) o[c] = 0.0f;
        am[M::kMean] = am[M::kMeanSquare] = 0.0f;
        continue;
      }
      const bool moving = view.cameraMoved || mv[0] * mv[0] + mv[1] * mv[1] > motionPx * motionPx;
      float hr = H / total;
      if (moving && rays > 0) hr = hc;
      const Vec3 nearC = H > 1e-6f ? dof::rgbAt(an, A::kRgb) * (1.0f / H) : Vec3(0.0f);
      const Vec3 farC = F > 1e-6f ? dof::rgbAt(af, A::kRgb) * (1.0f / F) : Vec3(0.0f);
      const float nearCoc = H > 1e-6f ? an[A::kCoc] / H : 0.0f;
      const float farCoc = F > 1e-6f ? af[A::kCoc] / F : 0.0f;
      if (H <= 1e-6f) hr = 0.0f;
      if (F <= 1e-6f) hr = 1.0f;
      const Vec3 c = lerp(farC, nearC, hr);
      using C = dof::RtChannels;
      o[C::kRgb] = c.x, o[C::kRgb + 1] = c.y, o[C::kRgb + 2] = c.z;
      // Temporal moments of each frame's merged ray-traced luminance (Schied et al. 2017), and
      // from them the variance of the accumulated mean (the frames' variance over the number
      // the moving average effectively holds): large at new or changing content and at
      // unconverged bokeh, small where the accumulation has converged.
      if (rays > 0) {
        am[M::kMean] = hm[M::kMean] + (lum - hm[M::kMean]) * alpha;
        am[M::kMeanSquare] = hm[M::kMeanSquare] + (lum * lum - hm[M::kMeanSquare]) * alpha;
      } else {
        am[M::kMean] = hm[M::kMean], am[M::kMeanSquare] = hm[M::kMeanSquare];
      }
      const float frames = std::min(std::max(am[M::kFrames], 1.0f), (2.0f - minAlpha) / minAlpha);
      variance.at(x, y)[0] =
          std::max(am[M::kMeanSquare] - am[M::kMean] * am[M::kMean], 0.0f) / frames;
      o[C::kCoc] = farCoc + (nearCoc - farCoc) * hr;
      o[C::kHit] = hr;
      o[C::kCoverage] = 1.0f;
      o[C::kNear] = nearC.x, o[C::kNear + 1] = nearC.y, o[C::kNear + 2] = nearC.z;
    }
  });
  double mean = 0, above = 0;
  for (float v : variance.data) mean += v, above += v > 1e-6f;
  const double n = double(std::max<size_t>(1, variance.data.size()));
  ctx.report(*this, DofAccumulationCounters::meanVariance, mean / n);
  // Share of pixels whose variance alone adds a ray at m = 10 with the paper's weight 1e5.
  ctx.report(*this, DofAccumulationCounters::varianceAbove1e6, above / n);
  Buffer& varOut = ctx.output(*this, Slots::dofVariance, w, h);
  varOut.data = gaussianBlur(variance, settings().varianceBlur).data;
}

}  // namespace tandem
