#include "passes/baselines/rt_whitted.h"

#include "passes/common/whitted_settings.h"
#include "pipeline/frame_context.h"
#include "rt/primary_rays.h"
#include "rt/whitted.h"
#include "shading/surface_resolve.h"

namespace tandem {

const ParamTable<RTWhittedSettings>& RTWhittedPass::tableFor() const {
  static const ParamTable<RTWhittedSettings> table =
      ParamTable<RTWhittedSettings>().nest(&RTWhittedSettings::whitted, whittedTable());
  return table;
}

void RTWhittedPass::execute(FrameContext& ctx) {
  WhittedFrame wf(ctx, *this, settings().whitted);
  const Scene& scene = *ctx.scene;
  Buffer& hdr = ctx.output(*this, Slots::hdr);
  Buffer& ids = ctx.output(*this, Slots::objectId);
  for (const View& v : ctx.views) {
    const float spread = ctx.pixelSpread(v);  // the pixel's cone picks texture LOD
    tracePrimaryBlocks(
        v.jitteredCamera, wf.rt,
        [&](int n, const int* px, const int* py, const Ray* rs, const Hit* hits) {
          // The block's surfaces are shaded together: shadow rays as packets, one batch.
          SurfaceSample s[8];
          Vec3 d[8], rgb[8];
          int at[8], m = 0;
          for (int k = 0; k < n; ++k) {
            const int x = px[k] + v.x, y = py[k] + v.y;
            const Hit& h = hits[k];
            ids.at(x, y)[0] = h.valid() ? float(h.object) : -1.0f;
            if (!h.valid()) {
              hdr.setRgb(x, y, scene.skyRadiance(rs[k].dir));
              continue;
            }
            const float tuv[3] = {h.t, h.u, h.v};  // Embree's hit: no second intersection
            s[m] = resolveSurface(ctx.frame, h.object, h.prim, rs[k].origin, rs[k].dir, rs[k].time,
                                  tuv, spread);
            d[m] = rs[k].dir;
            at[m++] = k;
          }
          wf.whitted.shadePrimary8(s, d, m, rgb);
          for (int j = 0; j < m; ++j) hdr.setRgb(px[at[j]] + v.x, py[at[j]] + v.y, rgb[j]);
        });
  }
  wf.finish(ctx, *this, double(ctx.width) * double(ctx.height));
}

}  // namespace tandem
