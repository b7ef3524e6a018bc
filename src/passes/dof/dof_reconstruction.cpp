#include "passes/dof/dof_reconstruction.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/image_filters.h"
#include "core/parallel.h"
#include "gpu/shaders/dof_args.h"
#include "gpu/shaders/dof_reconstruction_spv.h"
#include "passes/dof/dof_common.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"

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

namespace {
// The taps' directions: the centre, then rings of 8 and 16 (the second turned by half a step),
// the same for every pixel (and on both devices).
struct Tap {
  int ring;
  float cos, sin;
};
std::vector<Tap> reconstructionTaps() {
  std::vector<Tap> taps;
  for (int ring = 0; ring <= 2; ++ring) {
    const int n = ring == 0 ? 1 : 8 * ring;
    for (int k = 0; k < n; ++k) {
      const float a = 2.0f * kPi * (float(k) + 0.5f * float(ring & 1)) / float(n);
      taps.push_back({ring, std::cos(a), std::sin(a)});
    }
  }
  return taps;
}
}  // namespace

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
  const std::vector<Tap> taps = reconstructionTaps();
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

void DofReconstructionPass::executeGpu(FrameContext& ctx) {
  static_assert(TD_COMPOSITE_RT_CHANNELS == dof::RtChannels::kCount && dof::RtChannels::kCoc == 3 &&
                dof::RtChannels::kCoverage == 5);
  GpuFrame& gpu = *ctx.gpu;
  GpuCommands& cmd = gpu.commands();
  const Buffer& in = ctx.input(*this, Slots::rtColor);  // shapes (the values are on the device)
  const Buffer& variance = ctx.input(*this, Slots::dofVariance);
  if (!variance.sameShape(Buffer(in.width, in.height, 1)))
    throw std::logic_error("dof_reconstruction: dof_variance is not rt_color's size");
  const int w = in.width, h = in.height;
  constexpr size_t N = dof::RtChannels::kCount;
  DofReconstructionArgs a{};
  a.rtColor = ctx.deviceInput(*this, Slots::rtColor);
  a.variance = ctx.deviceInput(*this, Slots::dofVariance);
  a.rtRecon = ctx.deviceOutput(*this, Slots::rtRecon, w, h);
  const auto scratch = [&](const std::string& what, size_t floats) {
    return gpu.scratch("dof_reconstruction:" + name() + ":" + what, floats * sizeof(float)).address;
  };
  a.filtered = settings().median ? scratch("filtered", size_t(w) * h * N) : a.rtColor;
  std::vector<float> taps;
  for (const Tap& t : reconstructionTaps()) taps.insert(taps.end(), {float(t.ring), t.cos, t.sin});
  if (taps.size() != 3 * TD_RECON_TAPS) throw std::logic_error("dof_reconstruction: tap count");
  a.taps = gpu.constants(taps.data(), taps.size() * sizeof(float));
  // The mip levels (as downsampleBox halves them, while both sides exceed 1).
  a.levels = 1;
  a.mipWidth[0] = w;
  a.mipHeight[0] = h;
  while (a.levels < TD_RECON_LEVELS && a.mipWidth[a.levels - 1] > 1 &&
         a.mipHeight[a.levels - 1] > 1) {
    a.mipWidth[a.levels] = (a.mipWidth[a.levels - 1] + 1) / 2;
    a.mipHeight[a.levels] = (a.mipHeight[a.levels - 1] + 1) / 2;
    ++a.levels;
  }
  for (uint32_t l = 0; l < a.levels; ++l)
    a.mips[l] = scratch("mip" + std::to_string(l), size_t(a.mipWidth[l]) * a.mipHeight[l] * N);
  a.width = uint32_t(w);
  a.height = uint32_t(h);
  a.varianceWeight = settings().varianceWeight;
  a.lodScale = settings().lodScale;
  a.scale = float(ctx.width) / float(w);  // CoC is in frame pixels
  const GpuKernel& k = gpu.kernel("dof_reconstruction", kDofReconstructionSpv,
                                  sizeof(kDofReconstructionSpv) / 4, sizeof(DofStagePush));
  const auto stage = [&](uint32_t which, const DofReconstructionArgs& args, uint32_t gw,
                         uint32_t gh) {
    const DofStagePush push{gpu.constants(&args, sizeof args), which, 0};
    cmd.dispatch(k, (gw + 7) / 8, (gh + 7) / 8, 1, &push);
    cmd.barrier();
  };
  if (settings().median) stage(TD_RECON_MEDIAN, a, a.width, a.height);
  stage(TD_RECON_PREMULTIPLY, a, a.width, a.height);
  for (uint32_t l = 1; l < a.levels; ++l) {
    DofReconstructionArgs d = a;
    d.src = a.mips[l - 1];
    d.dst = a.mips[l];
    d.srcWidth = uint32_t(a.mipWidth[l - 1]);
    d.srcHeight = uint32_t(a.mipHeight[l - 1]);
    d.dstWidth = uint32_t(a.mipWidth[l]);
    d.dstHeight = uint32_t(a.mipHeight[l]);
    stage(TD_RECON_DOWNSAMPLE, d, d.dstWidth, d.dstHeight);
  }
  stage(TD_RECON_GATHER, a, a.width, a.height);
}

}  // namespace tandem
