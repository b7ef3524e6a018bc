#include "passes/common/downsample.h"

#include "core/image_filters.h"
#include "pipeline/frame_context.h"

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

}  // namespace tandem
