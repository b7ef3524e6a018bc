// nh_denoise on the GPU (shaders/nh_denoise.comp): the planes set up, L̄ (and each region's
// noise) reduced on the device, with the variance colour weight its prefilters, then Algorithm
// 1's levels region by region, ping-ponging two states, and the output. Only levels_from = variance
// reads anything back: the regions' noise, at a checkpoint, to choose their level counts as the CPU
// does.
#include <algorithm>
#include <cmath>
#include <vector>

#include "gpu/shaders/nh_denoise_args.h"
#include "gpu/shaders/nh_denoise_spv.h"
#include "passes/foveated/gpu_primary_surfaces.h"
#include "passes/foveated/nh_denoise.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"

namespace tandem {

namespace {

// The level counts of the regions of mode `regions` (one, two, three) from the settings.
std::vector<int> fixedLevels(const NHDenoiseSettings& s) {
  const int mode = int(s.regions);
  const int levels[3] = {s.levelsInner, s.levelsMiddle, s.levelsOuter};
  std::vector<int> out(size_t(mode + 1));
  for (int r = 0; r <= mode; ++r)
    out[size_t(r)] = mode == 0 ? levels[2] : (mode == 1 && r == 1) ? levels[2] : levels[r];
  return out;
}

}  // namespace

void NHDenoisePass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  GpuCommands& cmd = gpu.commands();
  const NHDenoiseSettings& s = settings();
  const uint32_t W = uint32_t(ctx.width), H = uint32_t(ctx.height);
  NhDenoiseArgs a{};
  a.views = gpuEyeViews(ctx);
  a.noisy = ctx.deviceInput(*this, Slots::ptNoisy);
  a.variance =
      ctx.optionalInput(*this, Slots::ptVariance) ? ctx.deviceInput(*this, Slots::ptVariance) : 0;
  a.direct =
      s.split == NHDenoiseSettings::Split::Direct && ctx.optionalInput(*this, Slots::ptDirect)
          ? ctx.deviceInput(*this, Slots::ptDirect)
          : 0;
  a.normal = ctx.deviceInput(*this, Slots::normal);
  a.position = ctx.deviceInput(*this, Slots::position);
  a.depth = ctx.deviceInput(*this, Slots::depth);
  a.diffuse = ctx.deviceInput(*this, Slots::diffuse);
  a.emission = ctx.deviceInput(*this, Slots::emission);
  a.mask = ctx.deviceInput(*this, Slots::fovMask);
  a.layer = ctx.deviceInput(*this, Slots::fovLayer);
  a.denoised = ctx.deviceOutput(*this, Slots::denoised);
  const size_t pixels = size_t(W) * H;
  const uint32_t gx = (W + 15) / 16, gy = (H + 15) / 16;
  a.groups = gx * gy;
  a.guided = s.colorWeight == NHDenoiseSettings::ColorWeight::Variance && a.variance != 0;
  a.stateFloats = a.guided ? 9 : 5;
  a.state[0] = gpu.scratch(name() + ":state0", pixels * a.stateFloats * sizeof(float)).address;
  a.state[1] = gpu.scratch(name() + ":state1", pixels * a.stateFloats * sizeof(float)).address;
  a.partials = gpu.scratch(name() + ":partials", size_t(a.groups) * TD_NH_PARTIALS * 4).address;
  const uint32_t zeroCounts[TD_NH_COUNTS] = {};
  const float zeroStats[TD_NH_STATS] = {};
  a.counts = gpu.constants(zeroCounts, sizeof zeroCounts);
  a.stats = gpu.constants(zeroStats, sizeof zeroStats);
  a.width = W;
  a.height = H;
  a.viewCount = uint32_t(ctx.views.size());
  a.regions = uint32_t(s.regions);
  a.demodulate = s.demodulate ? 1u : 0u;
  a.sigmaColor = s.sigmaColor;
  a.sigmaNormal = s.sigmaNormal;
  a.sigmaPosition = s.sigmaPosition;
  a.sigmaVariance = s.sigmaVariance;
  const uint64_t args = gpu.constants(&a, sizeof a);
  const GpuKernel& k =
      gpu.kernel("nh_denoise", kNhDenoiseSpv, sizeof(kNhDenoiseSpv) / 4, sizeof(NhStagePush));
  NhStagePush push{args, TD_NH_SETUP, 0, 0, 0, 0, 0};
  const auto stage = [&](uint32_t which, uint32_t x, uint32_t y) {
    push.stage = which;
    cmd.dispatch(k, x, y, 1, &push);
    cmd.barrier();
  };
  const bool fromNoise = s.levelsFrom == NHDenoiseSettings::LevelsFrom::Variance;
  stage(TD_NH_SETUP, gx, gy);
  if (fromNoise) stage(TD_NH_NOISE, gx, gy);
  stage(TD_NH_REDUCE, 1, 1);
  if (a.guided) {  // state 0 -> 1 -> 0, then the guide in place
    stage(TD_NH_PREFILTER, gx, gy);
    push.from = 1;
    stage(TD_NH_PREFILL, gx, gy);
    push.from = 0;
    stage(TD_NH_GUIDE, gx, gy);
  }
  const auto* counts = static_cast<const uint32_t*>(gpu.constantsData(a.counts));
  const auto* stats = static_cast<const float*>(gpu.constantsData(a.stats));
  std::vector<int> levels = fixedLevels(s);
  if (fromNoise) {
    // The noise per pixel area over the target, as the CPU chooses (NHDenoisePass::execute).
    cmd.checkpoint();
    const double mean = stats[TD_NH_MEAN];
    for (size_t r = 0; r < levels.size(); ++r) {
      const double total = counts[TD_NH_TOTAL + r], listed = counts[TD_NH_LISTED + r];
      const double density = total > 0 ? listed / total : 0.0;
      const double perArea = stats[TD_NH_NOISE_R + r] / (mean * mean) / std::max(density, 1e-3);
      levels[r] = std::clamp(
          int(std::ceil(std::log(std::max(perArea / s.targetVariance, 1.0)) / std::log(4.0))), 1,
          10);
      ctx.report(*this, NHDenoiseCounters::levelsRegion(int(r)), levels[r]);
    }
  }
  // Algorithm 1: the regions in order, each with step widths 2^(levels-1) ... 1.
  std::vector<std::pair<int, int>> steps;
  for (size_t r = 0; r < levels.size(); ++r) {
    if (fromNoise && counts[TD_NH_TOTAL + r] == 0) continue;  // an empty region runs no level
    for (int level = levels[r] - 1, it = 0; level >= 0; --level, ++it) {
      push.step = 1 << level;
      push.iteration = it;
      push.region = int32_t(r);
      stage(TD_NH_LEVEL, gx, gy);
      push.from ^= 1u;
      steps.push_back({int(r), 1 << level});
    }
  }
  stage(TD_NH_OUTPUT, gx, gy);
  gpu.afterSubmit([this, &ctx, counts, steps = std::move(steps)] {
    steps_.clear();
    for (const auto& st : steps)  // levels of a region with no pixel did nothing
      if (counts[TD_NH_TOTAL + st.first] > 0) steps_.push_back(st);
    ctx.report(*this, NHDenoiseCounters::levelsRun, double(steps_.size()));
  });
}

}  // namespace tandem
