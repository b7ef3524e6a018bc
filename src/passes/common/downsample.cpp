#include "passes/common/downsample.h"

#include "core/image_filters.h"
#include "gpu/shaders/downsample_args.h"
#include "gpu/shaders/downsample_spv.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"

namespace tandem {

const ParamTable<DownsampleSettings>& DownsamplePass::tableFor() const {
  using S = DownsampleSettings;
  static const ParamTable<S> table = ParamTable<S>().add(
      &S::filter, {.name = "filter", .doc = "reduction filter", .choices = {"box", "bilinear"}});
  return table;
}

void DownsamplePass::execute(FrameContext& ctx) {
  const Buffer& hdr = ctx.input(*this, Slots::hdr);
  Buffer& half = ctx.output(*this, Slots::half);
  Buffer& quarter = ctx.output(*this, Slots::quarter);
  const bool box = settings().filter == DownsampleSettings::Filter::Box;
  half.data = (box ? downsampleBox(hdr) : resizeBilinear(hdr, half.width, half.height)).data;
  quarter.data =
      (box ? downsampleBox(half) : resizeBilinear(hdr, quarter.width, quarter.height)).data;
}

void DownsamplePass::executeGpu(FrameContext& ctx) {
  const Buffer& hdr = ctx.input(*this, Slots::hdr);
  const Buffer& halfShape = ctx.shapedOutput(*this, Slots::half, 0, 0);
  const Buffer& quarterShape = ctx.shapedOutput(*this, Slots::quarter, 0, 0);
  const bool box = settings().filter == DownsampleSettings::Filter::Box;
  DownsampleArgs a{};
  a.channels = uint32_t(hdr.channels);
  a.mode = box ? TD_DOWNSAMPLE_BOX : TD_DOWNSAMPLE_BILINEAR;
  const uint64_t src = ctx.deviceInput(*this, Slots::hdr);
  const uint64_t half = ctx.deviceOutput(*this, Slots::half);
  const uint64_t quarter = ctx.deviceOutput(*this, Slots::quarter);
  GpuFrame& gpu = *ctx.gpu;
  GpuCommands& cmd = gpu.commands();
  const GpuKernel& k =
      gpu.kernel("downsample", kDownsampleSpv, sizeof(kDownsampleSpv) / 4, sizeof a);
  const auto reduce = [&](uint64_t from, int fw, int fh, uint64_t to, int tw, int th) {
    a.src = from, a.dst = to;
    a.srcWidth = fw, a.srcHeight = fh, a.dstWidth = tw, a.dstHeight = th;
    cmd.dispatch(k, uint32_t(tw + 7) / 8, uint32_t(th + 7) / 8, 1, &a);
  };
  reduce(src, hdr.width, hdr.height, half, halfShape.width, halfShape.height);
  if (box) {  // the quarter from the half, as the CPU reduces it
    cmd.barrier();
    reduce(half, halfShape.width, halfShape.height, quarter, quarterShape.width,
           quarterShape.height);
  } else {
    reduce(src, hdr.width, hdr.height, quarter, quarterShape.width, quarterShape.height);
  }
}

}  // namespace tandem
