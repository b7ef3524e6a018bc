#include "passes/dof_composite.h"

#include <cmath>

#include "core/image_filters.h"
#include "core/parallel.h"
#include "passes/dof_common.h"
#include "pipeline/frame_context.h"

namespace tandem {

std::vector<ParamDesc> DofCompositePass::params() const {
  return {{"mode",
           ParamType::Enum,
           0,
           0,
           1,
           "hybrid: eq. 7; rt: the ray-traced colour wherever there is one (rt-dof)",
           {"hybrid", "rt"}},
          {"far_blend", ParamType::Float, 0.3, 0.001, 1, "eq. 7: smoothstep(0, far_blend, h)", {}},
          {"bokeh", ParamType::Bool, 1, 0, 1, "near field: post-process colour on bright bokeh", {}}};
}

void DofCompositePass::execute(FrameContext& ctx) {
  const Buffer& sharp = ctx.input(*this, "hdr");
  const Buffer& coc = ctx.input(*this, "coc");
  const Buffer* postfxIn = ctx.optionalInput(*this, "postfx");
  const Buffer* bokehIn = ctx.optionalInput(*this, "bokeh");
  const Buffer& postfx = postfxIn ? *postfxIn : sharp;
  const Buffer* rt = ctx.optionalInput(*this, "rt_recon");
  Buffer& out = ctx.output(*this, "dof");
  const bool rtMode = param("mode") == 1, useBokeh = param("bokeh") != 0;
  const float farBlend = float(param("far_blend"));
  const int W = sharp.width, H = sharp.height;
  const float sx = rt ? float(rt->width) / float(W) : 1.0f, sy = rt ? float(rt->height) / float(H) : 1.0f;
  parallelRows(H, [&](int y) {
    for (int x = 0; x < W; ++x) {
      const float c = coc.at(x, y)[0];
      float r[6] = {};
      if (rt) sampleBilinear(*rt, (float(x) + 0.5f) * sx, (float(y) + 0.5f) * sy, r);
      const float coverage = dof::saturate(r[5]);
      Vec3 rtc(0.0f);
      if (coverage > 0) rtc = Vec3(r[0], r[1], r[2]) * (1.0f / std::max(r[5], 1e-6f));
      const float hit = coverage > 0 ? r[4] / std::max(r[5], 1e-6f) : 0.0f;
      Vec3 col;
      if (rtMode) {
        col = lerp(sharp.rgb(x, y), rtc, coverage);
      } else if (std::abs(c) < dof::kZoneOfFocusCoc) {
        col = sharp.rgb(x, y);  // zone of focus (eq. 6)
      } else {
        const Vec3 pp = postfx.rgb(x, y);
        Vec3 traced;
        if (c < 0)  // near field: ray traced, post-process on bright bokeh
          traced = useBokeh && bokehIn ? lerp(rtc, pp, bokehIn->at(x, y)[0]) : rtc;
        else  // far field, eq. 7
          traced = lerp(rtc, pp, dof::smoothstep(0.0f, farBlend, hit));
        col = lerp(pp, traced, coverage);
      }
      out.setRgb(x, y, col);
    }
  });
}

}  // namespace tandem
