#include "passes/dof/dof_coc.h"

#include <limits>

#include "gpu/shaders/dof_args.h"
#include "gpu/shaders/dof_coc_spv.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"
#include "pipeline/view_tiles.h"
#include "scene/thin_lens.h"

namespace tandem {

void DofCocPass::execute(FrameContext& ctx) {
  const Buffer& position = ctx.input(*this, Slots::position);
  const Buffer& depth = ctx.input(*this, Slots::depth);
  Buffer& coc = ctx.output(*this, Slots::coc);
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    const ThinLens lens = ThinLens::of(v.camera);
    const Vec3 eye = v.camera.desc.position, fwd = v.camera.forward;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        float c = 0.0f;
        if (lens.active()) {
          const float z =
              depth.at(x, y)[0] > 0
                  ? dot(Vec3(position.at(x, y)[0], position.at(x, y)[1], position.at(x, y)[2]) -
                            eye,
                        fwd)
                  : std::numeric_limits<float>::infinity();
          c = lens.coc(z);
        }
        coc.at(x, y)[0] = c;
      }
  });
}

void DofCocPass::executeGpu(FrameContext& ctx) {
  DofCocArgs a{};
  a.position = ctx.deviceInput(*this, Slots::position);
  a.depth = ctx.deviceInput(*this, Slots::depth);
  a.coc = ctx.deviceOutput(*this, Slots::coc);
  a.frameWidth = uint32_t(ctx.width);
  GpuFrame& gpu = *ctx.gpu;
  const GpuKernel& k = gpu.kernel("dof_coc", kDofCocSpv, sizeof(kDofCocSpv) / 4, sizeof a);
  for (const View& v : ctx.views) {
    const ThinLens lens = ThinLens::of(v.camera);
    const Vec3 eye = v.camera.desc.position, fwd = v.camera.forward;
    a.eyeX = eye.x, a.eyeY = eye.y, a.eyeZ = eye.z;
    a.forwardX = fwd.x, a.forwardY = fwd.y, a.forwardZ = fwd.z;
    a.aperture = lens.aperture;
    a.focus = lens.focus;
    a.pixelsPerSlope = lens.pixelsPerSlope;
    a.lensActive = lens.active() ? 1 : 0;
    a.viewX = uint32_t(v.x);
    a.viewY = uint32_t(v.y);
    a.width = uint32_t(v.width());
    a.height = uint32_t(v.height());
    gpu.commands().dispatch(k, (a.width + 7) / 8, (a.height + 7) / 8, 1, &a);
  }
}

}  // namespace tandem
