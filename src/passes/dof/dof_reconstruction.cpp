#include "passes/dof/dof_reconstruction.h"

#include <cmath>
#include <vector>

#include "core/image_filters.h"
#include "core/parallel.h"
#include "passes/dof/dof_common.h"
#include "pipeline/frame_context.h"

namespace tandem {

const ParamTable<DofReconstructionSettings>& DofReconstructionPass::tableFor() const {
  using S = DofReconstructionSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::varianceWeight, {.name = "variance_weight",
                                    .min = 0,
                                    .max = 1e9,
                                    .doc = "eq. 5: b = clamp(σ²·w, 0, 0.9)"})
          .add(&S::lodScale,
               {.name = "lod_scale", .min = 0, .max = 10, .doc = "eq. 8: lod = clamp(c_t·k, 0, 3)"})
          .add(&S::median, {.name = "median", .doc = "3x3 median before the reconstruction"});
  return table;
}

void DofReconstructionPass::execute(FrameContext& ctx) {
  const Buffer& in = ctx.input(*this, Slots::rtColor);
  const Buffer& variance = ctx.input(*this, Slots::dofVariance);
  const int w = in.width, h = in.height;
  Buffer& out = ctx.output(*this, Slots::rtRecon, w, h);
  const Buffer filtered = settings().median ? median3x3(in) : in;
  // Mip levels 0..3 of colour, CoC and hit ratio premultiplied by coverage, so uncovered
  // pixels do not darken the coarser levels.
  constexpr int N = dof::RtChannels::kCount, kCov = dof::RtChannels::kCoverage,
                kCoc = dof::RtChannels::kCoc;
  Buffer premul = filtered;
  for (size_t i = 0; i < premul.pixelCount(); ++i) {
    float* p = &premul.data[i * N];
    for (int c = 0; c < N; ++c)
      if (c != kCov) p[c] *= p[kCov];
  }
  std::vector<Buffer> mips = {premul};
  while (mips.size() < 4 && mips.back().width > 1 && mips.back().height > 1)
    mips.push_back(downsampleBox(mips.back()));
  const float vw = settings().varianceWeight, lodScale = settings().lodScale;
  const float scale = float(ctx.width) / float(w);  // CoC is in frame pixels
  // The taps' directions: the centre, then rings of 8 and 16 (the second turned by half a step),
  // the same for every pixel.
  struct Tap {
    int ring;
    float cos, sin;
  };
  std::vector<Tap> taps;
  for (int ring = 0; ring <= 2; ++ring) {
    const int n = ring == 0 ? 1 : 8 * ring;
    for (int k = 0; k < n; ++k) {
      const float a = 2.0f * kPi * (float(k) + 0.5f * float(ring & 1)) / float(n);
      taps.push_back({ring, std::cos(a), std::sin(a)});
    }
  }
  parallelRows(h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const float* c0 = filtered.at(x, y);
      float* o = out.at(x, y);
      for (int c = 0; c < N; ++c) o[c] = c0[c];
      if (c0[kCov] <= 0) continue;
      const float b = std::clamp(variance.at(x, y)[0] * vw, 0.0f, 0.9f);  // eq. 5
      const float radius = 0.5f * c0[kCoc] / scale;  // this resolution's pixels
      // Below 1/256 the lerp cannot change an 8-bit display value by more than one step of the
      // difference: skip the gather.
      if (b < 1.0f / 256.0f || radius < 0.5f) continue;
      const float lod = std::clamp(c0[kCoc] * lodScale, 0.0f, float(mips.size() - 1));  // eq. 8
      const int level = int(lod);
      const Buffer& mip = mips[size_t(level)];
      const float ms = float(mip.width) / float(w);
      float acc[N] = {};
      for (const Tap& t : taps) {
        const float r = radius * float(t.ring) / 2.0f;
        const float sx = float(x) + 0.5f + r * t.cos, sy = float(y) + 0.5f + r * t.sin;
        float s[N];
        sampleBilinearN<N>(mip, sx * ms, sy * ms, s);
        if (s[kCov] <= 1e-4f) continue;
        // Reject a tap whose own blur does not reach the centre: its CoC radius (the
        // coverage-weighted mean, 0.5 s[kCoc] / s[kCov] frame pixels) below r at this resolution.
        // Multiplied out: a division here stalled every tap's branch.
        if (t.ring > 0 && 0.5f * s[kCoc] < r * scale * s[kCov]) continue;
        for (int c = 0; c < N; ++c) acc[c] += s[c];
      }
      if (acc[kCov] <= 1e-4f) continue;
      const float inv = 1.0f / acc[kCov];
      for (int c = 0; c < N; ++c)
        if (c != kCov) o[c] = c0[c] + (acc[c] * inv - c0[c]) * b;
    }
  });
}

}  // namespace tandem
