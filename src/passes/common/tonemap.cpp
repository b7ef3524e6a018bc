#include "passes/common/tonemap.h"

#include "core/color.h"
#include "core/parallel.h"
#include "gpu/shaders/tonemap_args.h"
#include "gpu/shaders/tonemap_spv.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"

namespace tandem {

const ParamTable<TonemapSettings>& TonemapPass::tableFor() const {
  using S = TonemapSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::exposure,
               {.name = "exposure", .min = -20, .max = 20, .doc = "exposure in stops (scale 2^EV)"})
          .add(&S::op,
               {.name = "operator", .doc = "tone curve", .choices = {"clamp", "reinhard", "aces"}});
  return table;
}

void TonemapPass::execute(FrameContext& ctx) {
  const Buffer& hdr = ctx.input(*this, Slots::hdr);
  Buffer& out = ctx.output(*this, Slots::output);
  const float ev = settings().exposure;
  const auto op = settings().op;
  parallelTiles(ctx.width, ctx.height, [&](int x0, int y0, int x1, int y1) {
    for (int y = y0; y < y1; ++y) {
      const size_t i = (size_t(y) * size_t(ctx.width) + size_t(x0)) * 3;
      tonemapSpan(hdr.data.data() + i, out.data.data() + i, size_t(x1 - x0) * 3, ev, op);
    }
  });
}

void TonemapPass::executeGpu(FrameContext& ctx) {
  const Buffer& hdr = ctx.input(*this, Slots::hdr);
  TonemapArgs a{};
  a.hdr = ctx.deviceInput(*this, Slots::hdr);
  a.display = ctx.deviceOutput(*this, Slots::output);
  a.count = uint32_t(hdr.data.size());
  a.scale = std::exp2(settings().exposure);
  a.op = uint32_t(settings().op);
  // A 2D grid: one invocation a value, rows of at most 65535 groups of 64.
  const uint32_t groups = (a.count + 63) / 64, gx = std::min<uint32_t>(groups, 65535);
  a.rowWidth = gx * 64;
  GpuFrame& gpu = *ctx.gpu;
  const GpuKernel& k = gpu.kernel("tonemap", kTonemapSpv, sizeof(kTonemapSpv) / 4, sizeof a);
  gpu.commands().dispatch(k, gx, (groups + gx - 1) / gx, 1, &a);
}

}  // namespace tandem
