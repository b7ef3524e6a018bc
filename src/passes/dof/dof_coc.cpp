#include "passes/dof/dof_coc.h"

#include <limits>

#include "pipeline/frame_context.h"
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

}  // namespace tandem
