#include "passes/dof/postfx_dof.h"

#include <array>
#include <cmath>
#include <limits>

#include "core/image_filters.h"
#include "core/parallel.h"
#include "passes/dof/dof_common.h"
#include "passes/dof/gather_taps.h"
#include "pipeline/frame_context.h"
#include "scene/thin_lens.h"

namespace tandem {

using dof::saturate;

const ParamTable<PostfxDofSettings>& PostfxDofPass::tableFor() const {
  using S = PostfxDofSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::depthRange, {.name = "depth_range",
                                .min = 0,
                                .max = 1e6,
                                .doc = "metres: a tap this much nearer than the centre is "
                                       "foreground (the paper: 10 cm)"})
          .add(&S::specularThreshold,
               {.name = "specular_threshold",
                .min = 0,
                .max = 1,
                .doc = "specular luminance from which a sample counts towards the bokeh intensity"})
          .add(&S::bokehLuminance,
               {.name = "bokeh_luminance",
                .min = 0,
                .max = 1e6,
                .doc = "luminance from which a high-specular sample is a bright highlight (bokeh)"})
          .add(&S::polygon,
               {.name = "polygon",
                .doc = "polygonal aperture (apertureBlades >= 3) in the gather kernel (beyond the "
                       "paper)"})
          .add(&S::median, {.name = "median", .doc = "3x3 median post-filter"});
  return table;
}

namespace dof {

GatherTaps gatherTaps(const ThinLens& lens, bool polygon, int64_t serial) {
  GatherTaps g{};
  const float rotation =
      2.0f * kPi * float((uint32_t(serial) * 2654435769u) >> 8) / float(1u << 24) / 81.0f;
  g.taps[0] = {0, 0, 0};
  int i = 1;
  for (int k = 1; k <= 4; ++k) {
    const int n = 8 * k;
    for (int j = 0; j < n; ++j, ++i) {
      const float a = rotation + 2.0f * kPi * (float(j) + 0.5f * float(k & 1)) / float(n);
      const float r = float(k) / 4.0f;
      g.taps[size_t(i)] = {r * std::cos(a), r * std::sin(a), r};
    }
  }
  for (size_t t = 0; t < g.taps.size(); ++t) {
    const float angle = std::atan2(-g.taps[t].y, -g.taps[t].x);  // from the tap to the centre
    g.extentFar[t] =
        polygon && t > 0 ? apertureExtent(lens.blades, lens.rotationDeg, angle, false) : 1.0f;
    g.extentNear[t] =
        polygon && t > 0 ? apertureExtent(lens.blades, lens.rotationDeg, angle, true) : 1.0f;
  }
  return g;
}

void prefilterDirection(int t, float& cosA, float& sinA) {
  const float a = 2.0f * kPi * float(t) / 8.0f;
  cosA = std::cos(a);
  sinA = std::sin(a);
}

}  // namespace dof

namespace {

using dof::Tap;
constexpr int kTile = dof::kPostfxTile;

struct HalfSample {
  float r, g, b;
  float coc;     // signed, in half-res pixels (diameter)
  float z;       // view depth, metres (the sky: 1e30)
  float spec;    // 1: a bright specular highlight
  float radius;  // |coc| / 2
  float alpha;   // sample alpha: 1 / (π r²), r at least half a pixel
};

// The half-resolution grid the filter runs on, with its tiles' neighbourhood max |CoC|.
struct HalfGrid {
  int W, H, hw, hh, tw, th;
  std::vector<HalfSample> half;
  std::vector<float> neighbourMax;
  float maxCocAt(int x, int y) const {
    return neighbourMax[size_t(y / kTile) * tw + size_t(x / kTile)];
  }
  const HalfSample& at(int x, int y) const {
    return half[size_t(std::clamp(y, 0, hh - 1)) * hw + size_t(std::clamp(x, 0, hw - 1))];
  }
};

HalfGrid downsample(const Buffer& hdr, const Buffer& cocIn, const Buffer& specIn,
                    const ThinLens& lens, float specThreshold, float bokehLuminance) {
  const int W = hdr.width, H = hdr.height, hw = (W + 1) / 2, hh = (H + 1) / 2;
  // CoC -> view depth (the inverse of ThinLens::coc; depth is what separates fg from bg).
  const float k = lens.aperture * lens.pixelsPerSlope;
  auto depthOf = [&](float cocFrame) {
    const float den = k - cocFrame * lens.focus;
    return den > 1e-9f ? k * lens.focus / den : 1e30f;  // the sky: far, finite (no inf - inf)
  };
  // Downsample CoC, depth and the high-specular flag (colour: the prefilter below).
  std::vector<HalfSample> half(size_t(hw) * hh);
  parallelRows(hh, [&](int y) {
    for (int x = 0; x < hw; ++x) {
      float cmin = std::numeric_limits<float>::infinity(), highlight = 0.0f;
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
          const int sx = std::min(2 * x + i, W - 1), sy = std::min(2 * y + j, H - 1);
          cmin = std::min(cmin, cocIn.at(sx, sy)[0]);
          // A bright specular highlight: a specular surface, and brighter than white.
          const float* s = specIn.at(sx, sy) + SpecularChannels::kRgb;
          if (luminance(Vec3(s[0], s[1], s[2])) >= specThreshold &&
              luminance(hdr.rgb(sx, sy)) >= bokehLuminance)
            highlight = 1.0f;
        }
      const float radius = 0.25f * std::abs(cmin);
      half[size_t(y) * hw + x] = {0,
                                  0,
                                  0,
                                  0.5f * cmin,
                                  depthOf(cmin),
                                  highlight,
                                  radius,
                                  1.0f / (kPi * std::max(radius * radius, 0.25f))};
    }
  });

  // Tile max |CoC| and its 3x3 neighbourhood max (half-res pixels, diameter).
  const int tw = (hw + kTile - 1) / kTile, th = (hh + kTile - 1) / kTile;
  std::vector<float> tileMax(size_t(tw) * th, 0.0f), neighbourMax(size_t(tw) * th, 0.0f);
  for (int y = 0; y < hh; ++y)
    for (int x = 0; x < hw; ++x) {
      float& m = tileMax[size_t(y / kTile) * tw + size_t(x / kTile)];
      m = std::max(m, std::abs(half[size_t(y) * hw + x].coc));
    }
  for (int ty = 0; ty < th; ++ty)
    for (int tx = 0; tx < tw; ++tx) {
      float m = 0.0f;
      for (int j = std::max(ty - 1, 0); j <= std::min(ty + 1, th - 1); ++j)
        for (int i = std::max(tx - 1, 0); i <= std::min(tx + 1, tw - 1); ++i)
          m = std::max(m, tileMax[size_t(j) * tw + i]);
      neighbourMax[size_t(ty) * tw + tx] = m;
    }
  return {W, H, hw, hh, tw, th, std::move(half), std::move(neighbourMax)};
}

HalfGrid prefilter(HalfGrid grid, const Buffer& hdr, const Buffer& cocIn) {
  const int W = grid.W, H = grid.H, hw = grid.hw, hh = grid.hh;
  // The 9-tap bilateral prefilter is the downsampling filter (Jimenez): bilinear taps of the
  // frame around each half-res pixel's centre, diameter 1/8 of the neighbourhood's max CoC but
  // at least √2 frame pixels (then it is a 2x2 average, no pixel sampled twice); taps of a very
  // different CoC (another surface) count less. CoC, depth and flags stay the downsample's.
  std::vector<HalfSample> pre(grid.half.size());
  parallelRows(hh, [&](int y) {
    for (int x = 0; x < hw; ++x) {
      const HalfSample& c0 = grid.at(x, y);
      const float maxCoc = grid.maxCocAt(x, y);
      const float radius = 0.5f * std::max(2.0f * maxCoc / 8.0f, dof::kZoneOfFocusCoc);
      const float cx = 2.0f * float(x) + 1.0f, cy = 2.0f * float(y) + 1.0f;  // frame coordinates
      float r = 0, g = 0, b = 0, wsum = 0;
      for (int t = 0; t < 9; ++t) {
        float cosA = 0, sinA = 0;
        if (t < 8) dof::prefilterDirection(t, cosA, sinA);
        const float px = t == 8 ? cx : cx + radius * cosA;
        const float py = t == 8 ? cy : cy + radius * sinA;
        float rgb[3];
        sampleBilinearN<3>(hdr, px, py, rgb);
        const float tc =
            0.5f * cocIn.at(std::clamp(int(px), 0, W - 1), std::clamp(int(py), 0, H - 1))[0];
        const float w = 1.0f / (1.0f + std::abs(tc - c0.coc));
        r += w * rgb[0];
        g += w * rgb[1];
        b += w * rgb[2];
        wsum += w;
      }
      HalfSample s = c0;
      s.r = r / wsum;
      s.g = g / wsum;
      s.b = b / wsum;
      pre[size_t(y) * hw + x] = s;
    }
  });

  grid.half = std::move(pre);
  return grid;
}

struct GatherSettings {
  float depthRange;
  bool polygon;
  int64_t serial;  // the executed frame (the rings' rotation)
};

// Eq. 1: the 81-tap gather, colour and (bokeh) the specular share and blurred foreground.
void gather(const HalfGrid& grid, const ThinLens& lens, const GatherSettings& gs, Buffer& gathered,
            Buffer& bokeh) {
  const int hw = grid.hw, hh = grid.hh;
  const std::vector<HalfSample>& pre = grid.half;
  const float depthRange = gs.depthRange;
  const bool polygon = gs.polygon;
  const dof::GatherTaps pattern = dof::gatherTaps(lens, polygon, gs.serial);
  const std::array<Tap, 81>& taps = pattern.taps;
  const std::array<float, 81>&extentFar = pattern.extentFar, &extentNear = pattern.extentNear;
  const float invRange = depthRange > 0 ? 1.0f / depthRange : 0.0f;
  const float nearFieldCoc = -0.5f * dof::kZoneOfFocusCoc;  // half-res pixels
  parallelRows(hh, [&](int y) {
    // Tap offsets for the current tile's kernel radius (recomputed when it changes).
    int dx[81], dy[81];
    float dist[81];
    float lastR = -1.0f;
    int reachX = 0, reachY = 0;
    for (int x = 0; x < hw; ++x) {
      const HalfSample& c0 = pre[size_t(y) * hw + x];
      const float R = 0.5f * grid.maxCocAt(x, y);
      if (R < 0.5f) {  // the whole neighbourhood is sharp
        gathered.setRgb(x, y, Vec3(c0.r, c0.g, c0.b));
        continue;
      }
      if (R != lastR) {
        lastR = R;
        reachX = reachY = 0;
        for (size_t i = 0; i < taps.size(); ++i) {
          dx[i] = int(std::lround(taps[i].x * R));
          dy[i] = int(std::lround(taps[i].y * R));
          dist[i] = taps[i].dist * R;
          reachX = std::max(reachX, std::abs(dx[i]));
          reachY = std::max(reachY, std::abs(dy[i]));
        }
      }
      const bool inside = x >= reachX && y >= reachY && x + reachX < hw && y + reachY < hh;
      const HalfSample* row = &pre[size_t(y) * hw + x];
      const float r0 = c0.radius;
      float fr = 0, fg = 0, fb = 0, wsum = 0, wfSum = 0, spec = 0, reach = 0;
      for (size_t i = 0; i < taps.size(); ++i) {
        const HalfSample& s = inside ? row[ptrdiff_t(dy[i]) * hw + dx[i]]
                                     : pre[size_t(std::clamp(y + dy[i], 0, hh - 1)) * hw +
                                           size_t(std::clamp(x + dx[i], 0, hw - 1))];
        // Foreground: nearer than the centre by more than the depth range (soft over one range).
        const float fgShare =
            depthRange > 0 ? saturate((c0.z - s.z) * invRange - 1.0f) : (s.z < c0.z ? 1.f : 0.f);
        // A background tap spreads no further than the centre's own blur; D(0, i) has a soft
        // edge of one pixel centred on the CoC radius.
        const float e = s.coc < 0 ? extentNear[i] : extentFar[i];
        const float dFg = i == 0 ? 1.0f : saturate(s.radius * e - dist[i] + 0.5f);
        const float dBg = i == 0 ? 1.0f : saturate(std::min(s.radius, r0) * e - dist[i] + 0.5f);
        const float dd = dBg + fgShare * (dFg - dBg);  // fgShare·dFg + (1 − fgShare)·dBg
        const float w = dd * s.alpha;
        fr += w * s.r;
        fg += w * s.g;
        fb += w * s.b;
        wsum += w;
        if (i > 0 && s.coc < nearFieldCoc) wfSum += fgShare * dFg * s.alpha;  // blurred foreground
        reach += dd;
        spec += dd * s.spec;
      }
      const float inv = 1.0f / std::max(wsum, 1e-20f);
      gathered.setRgb(x, y, Vec3(fr * inv, fg * inv, fb * inv));
      bokeh.at(x, y)[dof::BokehChannels::kIntensity] = reach > 0 ? spec / reach : 0.0f;
      bokeh.at(x, y)[dof::BokehChannels::kForeground] = wsum > 0 ? wfSum / wsum : 0.0f;
    }
  });
}

}  // namespace

void PostfxDofPass::execute(FrameContext& ctx) {
  const Buffer& hdr = ctx.input(*this, Slots::hdr);
  const Buffer& cocIn = ctx.input(*this, Slots::coc);
  const Buffer& specIn = ctx.input(*this, Slots::specular);
  Buffer& out = ctx.output(*this, Slots::postfx);
  Buffer& bokehOut = ctx.output(*this, Slots::bokeh);
  const ThinLens lens = ThinLens::of(ctx.camera());
  if (!lens.active()) {  // a pinhole: nothing to blur
    out.data = hdr.data;
    bokehOut.fill(0.0f);
    return;
  }
  // 1. Downsample CoC, depth and the high-specular flag; 2. tile max |CoC| and its 3x3
  // neighbourhood max; 3. the colour prefiltered.
  const HalfGrid grid = prefilter(
      downsample(hdr, cocIn, specIn, lens, settings().specularThreshold, settings().bokehLuminance),
      hdr, cocIn);
  // 4. The gather.
  Buffer gathered(grid.hw, grid.hh, 3), bokeh(grid.hw, grid.hh, dof::BokehChannels::kCount);
  gather(grid, lens, {settings().depthRange, settings().polygon && lens.blades >= 3, ctx.serial},
         gathered, bokeh);
  // 5. Median, upscale.
  const Buffer filtered = settings().median ? median3x3(gathered) : gathered;
  out.data = resizeBilinear(filtered, hdr.width, hdr.height).data;
  bokehOut.data = resizeBilinear(bokeh, hdr.width, hdr.height).data;
}

}  // namespace tandem
