#include "passes/dof/dof_composite.h"

#include <array>
#include <cmath>

#include "core/image_filters.h"
#include "core/parallel.h"
#include "gpu/shaders/dof_args.h"
#include "gpu/shaders/dof_composite_spv.h"
#include "passes/dof/dof_common.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"

namespace tandem {

const ParamTable<DofCompositeSettings>& DofCompositePass::tableFor() const {
  using S = DofCompositeSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::mode,
               {.name = "mode",
                .doc = "hybrid: eq. 7; rt: the ray-traced colour wherever there is one (rt-dof)",
                .choices = {"hybrid", "rt"}})
          .add(&S::farBlend, {.name = "far_blend",
                              .min = 0.001,
                              .max = 1,
                              .doc = "eq. 7: smoothstep(0, far_blend, h)"})
          .add(&S::bokeh,
               {.name = "bokeh", .doc = "near field: post-process colour on bright bokeh"})
          .add(&S::silhouette,
               {.name = "silhouette",
                .doc = "an in-focus pixel under a blurred foreground's rim: eq7 (as the far field) "
                       "or sharp_background: the raster colour and the traced near field by hit "
                       "ratio",
                .choices = {"eq7", "sharp_background"}})
          .add(&S::fineCoc,
               dof::fineCocParam(
                   "out of focus with no foreground over the pixel: below this |CoC| (px) the "
                   "sharp image gathered at full resolution instead of the upsampled rays / "
                   "gather (0 = off)"));
  return table;
}

namespace {
using dof::kSilhouette;
using Rt = dof::RtChannels;
constexpr int kRgb = Rt::kRgb, kHit = Rt::kHit, kCoverage = Rt::kCoverage;
constexpr int kIntensity = dof::BokehChannels::kIntensity,
              kForeground = dof::BokehChannels::kForeground;

// The distance of every pixel offset up to kMaxReach from the centre, row by row.
constexpr int kMaxReach = 33;  // ceil(64 / 2 + 0.5): fine_coc's largest radius
constexpr int kSpan = 2 * kMaxReach + 1;
const std::array<float, kSpan * kSpan>& offsetDistances() {
  static const auto table = [] {
    std::array<float, kSpan * kSpan> t{};
    for (int dy = -kMaxReach; dy <= kMaxReach; ++dy)
      for (int dx = -kMaxReach; dx <= kMaxReach; ++dx)
        t[size_t((dy + kMaxReach) * kSpan + dx + kMaxReach)] = std::sqrt(float(dx * dx + dy * dy));
    return t;
  }();
  return table;
}

// The sharp image gathered over a disc of `radius` pixels around (x, y) at full resolution. Each
// neighbour is weighted by how much of it the disc covers and by whether its own blur reaches the
// centre (scatter as gather, as the reconstruction's rejection), so an in-focus edge next to a
// blurred floor does not bleed into it.
Vec3 fineGather(const Buffer& sharp, const Buffer& coc, int x, int y, float radius) {
  const float reach = radius + 0.5f;
  const int r = std::min(int(std::ceil(reach)), kMaxReach);
  const float* dist = offsetDistances().data();
  float sum[3] = {0, 0, 0}, wsum = 0;
  for (int dy = std::max(-r, -y); dy <= std::min(r, sharp.height - 1 - y); ++dy) {
    // Only the disc's span of this row (the centre's weight is 1: |CoC| >= 0 reaches it).
    const int half = int(std::sqrt(std::max(reach * reach - float(dy * dy), 0.0f)));
    const int x0 = std::max(x - half, 0), x1 = std::min(x + half, sharp.width - 1);
    const float* drow = dist + (dy + kMaxReach) * kSpan + kMaxReach - x;
    const float* crow = coc.at(0, y + dy);
    const float* srow = sharp.at(0, y + dy);
    for (int xx = x0; xx <= x1; ++xx) {
      const float d = drow[xx];
      const float wt =
          dof::saturate(reach - d) * dof::saturate(0.5f * std::abs(crow[xx]) + 0.5f - d);
      sum[0] += srow[3 * xx] * wt;
      sum[1] += srow[3 * xx + 1] * wt;
      sum[2] += srow[3 * xx + 2] * wt;
      wsum += wt;
    }
  }
  const float inv = 1.0f / wsum;
  return Vec3(sum[0] * inv, sum[1] * inv, sum[2] * inv);
}
}  // namespace

void DofCompositePass::execute(FrameContext& ctx) {
  const Buffer& sharp = ctx.input(*this, Slots::hdr);
  const Buffer& coc = ctx.input(*this, Slots::coc);
  const Buffer* postfxIn = ctx.optionalInput(*this, Slots::postfx);
  const Buffer* bokehIn = ctx.optionalInput(*this, Slots::bokeh);
  const Buffer& postfx = postfxIn ? *postfxIn : sharp;
  const Buffer* rt = ctx.optionalInput(*this, Slots::rtRecon);
  Buffer& out = ctx.output(*this, Slots::dof);
  const DofCompositeSettings& s = settings();
  const bool rtMode = s.mode == DofCompositeSettings::Mode::Rt, useBokeh = s.bokeh;
  const float farBlend = s.farBlend;
  const bool sharpBackground = s.silhouette == DofCompositeSettings::Silhouette::SharpBackground;
  const float fineCoc = s.fineCoc;
  const int W = sharp.width, H = sharp.height;
  const float sx = rt ? float(rt->width) / float(W) : 1.0f,
              sy = rt ? float(rt->height) / float(H) : 1.0f;
  parallelRows(H, [&](int y) {
    for (int x = 0; x < W; ++x) {
      const float c = coc.at(x, y)[0];
      float r[dof::RtChannels::kCount] = {};
      if (rt)
        sampleBilinearN<dof::RtChannels::kCount>(*rt, (float(x) + 0.5f) * sx,
                                                 (float(y) + 0.5f) * sy, r);
      const float coverage = dof::saturate(r[kCoverage]);
      Vec3 rtc(0.0f);
      if (coverage > 0)
        rtc = Vec3(r[kRgb], r[kRgb + 1], r[kRgb + 2]) * (1.0f / std::max(r[kCoverage], 1e-6f));
      const float hit = coverage > 0 ? r[kHit] / std::max(r[kCoverage], 1e-6f) : 0.0f;
      const float* rn = &r[dof::RtChannels::kNear];
      const Vec3 rtNear = coverage > 0
                              ? Vec3(rn[0], rn[1], rn[2]) * (1.0f / std::max(r[kCoverage], 1e-6f))
                              : Vec3(0.0f);
      const bool inFocus = std::abs(c) < dof::kZoneOfFocusCoc;
      // A blurred foreground reaches over this pixel: some of its lens rays hit the near field,
      // or (without rays) the gather drew from foreground taps.
      const bool silhouette = coverage > 0
                                  ? hit > kSilhouette
                                  : bokehIn && bokehIn->at(x, y)[kForeground] > kSilhouette;
      const Vec3 pp = postfx.rgb(x, y);
      Vec3 col;
      if (rtMode) {
        col = lerp(sharp.rgb(x, y), rtc, coverage);
      } else if (inFocus && !silhouette) {
        col = sharp.rgb(x, y);  // zone of focus (eq. 6), no foreground over it
      } else if (inFocus && sharpBackground) {
        // A sharp surface behind a blurred foreground's rim: the share 1 - h of the lens that
        // sees past the foreground sees exactly the raster colour; the share h the near field.
        col = lerp(pp, lerp(sharp.rgb(x, y), rtNear, hit), coverage);
      } else {
        Vec3 traced;
        if (c < 0)  // near field: ray traced, post-process on bright bokeh
          traced = useBokeh && bokehIn ? lerp(rtc, pp, bokehIn->at(x, y)[kIntensity]) : rtc;
        else  // far field, eq. 7
          traced = lerp(rtc, pp, dof::smoothstep(0.0f, farBlend, hit));
        col = lerp(pp, traced, coverage);
        // Near focus the half-resolution rays and gather, upsampled, blur texture that a small
        // CoC leaves sharp. Where no nearer surface spreads over the pixel (the gather drew
        // nothing from foreground taps and, in the far field, no lens ray hit the near field),
        // a full-resolution gather of the sharp image is the same blur (beyond the paper).
        const float a = std::abs(c);
        const bool noForeground = bokehIn && bokehIn->at(x, y)[kForeground] <= kSilhouette &&
                                  (c < 0 || coverage <= 0 || hit <= kSilhouette);
        if (a < fineCoc && noForeground)
          col = lerp(col, fineGather(sharp, coc, x, y, 0.5f * a),
                     1.0f - dof::smoothstep(0.5f * fineCoc, fineCoc, a));
      }
      out.setRgb(x, y, col);
    }
  });
}

void DofCompositePass::executeGpu(FrameContext& ctx) {
  static_assert(TD_COMPOSITE_RT_CHANNELS == dof::RtChannels::kCount && kMaxReach == 33);
  const Buffer& sharp = ctx.input(*this, Slots::hdr);  // the shape (its value is on the device)
  const Buffer* rt = ctx.optionalInput(*this, Slots::rtRecon);
  const auto deviceIf = [&](const char* slot) {
    return ctx.optionalInput(*this, slot) ? ctx.deviceInput(*this, slot) : 0;
  };
  DofCompositeArgs a{};
  a.sharp = ctx.deviceInput(*this, Slots::hdr);
  a.coc = ctx.deviceInput(*this, Slots::coc);
  a.postfx = deviceIf(Slots::postfx);
  a.bokeh = deviceIf(Slots::bokeh);
  a.rt = deviceIf(Slots::rtRecon);
  a.dof = ctx.deviceOutput(*this, Slots::dof);
  a.width = uint32_t(sharp.width);
  a.height = uint32_t(sharp.height);
  a.rtWidth = rt ? uint32_t(rt->width) : 0;
  a.rtHeight = rt ? uint32_t(rt->height) : 0;
  a.scaleX = rt ? float(rt->width) / float(sharp.width) : 1.0f;
  a.scaleY = rt ? float(rt->height) / float(sharp.height) : 1.0f;
  const DofCompositeSettings& s = settings();
  a.rtMode = s.mode == DofCompositeSettings::Mode::Rt ? 1 : 0;
  a.useBokeh = s.bokeh ? 1 : 0;
  a.sharpBackground = s.silhouette == DofCompositeSettings::Silhouette::SharpBackground ? 1 : 0;
  a.farBlend = s.farBlend;
  a.fineCoc = s.fineCoc;
  GpuFrame& gpu = *ctx.gpu;
  const GpuKernel& k =
      gpu.kernel("dof_composite", kDofCompositeSpv, sizeof(kDofCompositeSpv) / 4, sizeof a);
  gpu.commands().dispatch(k, (a.width + 7) / 8, (a.height + 7) / 8, 1, &a);
}

}  // namespace tandem
