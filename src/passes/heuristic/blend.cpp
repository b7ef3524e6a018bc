#include "passes/heuristic/blend.h"

#include "core/parallel.h"
#include "gpu/shaders/blend_args.h"
#include "gpu/shaders/blend_spv.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"
#include "rt/whitted.h"

namespace tandem {

void BlendPass::execute(FrameContext& ctx) {
  const Buffer& L = ctx.input(*this, Slots::hdr);
  const Buffer& S = ctx.input(*this, Slots::shadow);
  const Buffer& M = ctx.input(*this, Slots::reflection);
  const Buffer& R = ctx.input(*this, Slots::refraction);
  const Buffer& optical = ctx.input(*this, Slots::optical);
  const Buffer& mask = ctx.input(*this, Slots::heuristicMask);
  Buffer& out = ctx.output(*this, Slots::composite);
  const Buffer* fallback = ctx.optionalInput(*this, Slots::fallback);
  parallelTiles(ctx.width, ctx.height, [&](int x0, int y0, int x1, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const float* m = mask.at(x, y);
        const float* fb = fallback ? fallback->at(x, y) : nullptr;
        const bool hasFallback = fb && fb[fallback::kCoversEffect] > 0.5f,
                   hasShadowFallback = fb && fb[fallback::kCoversShadow] > 0.5f;
        if (m[kShadow] < 0.5f && m[kReflection] < 0.5f && m[kRefraction] < 0.5f && !hasFallback &&
            !hasShadowFallback) {
          out.setRgb(x, y, L.rgb(x, y));
          continue;
        }
        // An effect that was not traced for this pixel plays no part (no shadowing, O_M or O_R
        // taken as 0), as for an unselected object, unless a fallback stands in for it.
        const float* op = optical.at(x, y);
        const bool traceM = m[kReflection] > 0.5f, traceR = m[kRefraction] > 0.5f;
        const float om = traceM || hasFallback ? op[OpticalChannels::kReflectivity] : 0.0f;
        const float orr = traceR || hasFallback ? 1.0f - op[OpticalChannels::kOpacity] : 0.0f;
        const Vec3 refl = traceM        ? M.rgb(x, y)
                          : hasFallback ? loadVec3(fb + fallback::kReflection)
                                        : Vec3(0.0f);
        const Vec3 refr = traceR        ? R.rgb(x, y)
                          : hasFallback ? loadVec3(fb + fallback::kRefraction)
                                        : Vec3(0.0f);
        Vec3 c = L.rgb(x, y);
        if (m[kShadow] > 0.5f)
          c = c - (Vec3(1.0f) - S.rgb(x, y));  // eq. 4
        else if (hasShadowFallback)
          c = c - (Vec3(1.0f) - loadVec3(fb + fallback::kShadow));
        out.setRgb(x, y, combineEffects(om, orr, refl, refr, c));
      }
  });
}

void BlendPass::executeGpu(FrameContext& ctx) {
  static_assert(TD_FALLBACK_CHANNELS == fallback::kChannels &&
                TD_FALLBACK_COVERS_EFFECT == fallback::kCoversEffect &&
                TD_FALLBACK_COVERS_SHADOW == fallback::kCoversShadow &&
                TD_FALLBACK_SHADOW == fallback::kShadow &&
                TD_FALLBACK_REFLECTION == fallback::kReflection &&
                TD_FALLBACK_REFRACTION == fallback::kRefraction);
  BlendArgs a{};
  a.hdr = ctx.deviceInput(*this, Slots::hdr);
  a.shadow = ctx.deviceInput(*this, Slots::shadow);
  a.reflection = ctx.deviceInput(*this, Slots::reflection);
  a.refraction = ctx.deviceInput(*this, Slots::refraction);
  a.optical = ctx.deviceInput(*this, Slots::optical);
  a.mask = ctx.deviceInput(*this, Slots::heuristicMask);
  a.fallback =
      ctx.optionalInput(*this, Slots::fallback) ? ctx.deviceInput(*this, Slots::fallback) : 0;
  a.composite = ctx.deviceOutput(*this, Slots::composite);
  a.width = uint32_t(ctx.width);
  a.height = uint32_t(ctx.height);
  GpuFrame& gpu = *ctx.gpu;
  const GpuKernel& k = gpu.kernel("blend", kBlendSpv, sizeof(kBlendSpv) / 4, sizeof a);
  gpu.commands().dispatch(k, (a.width + 7) / 8, (a.height + 7) / 8, 1, &a);
}

}  // namespace tandem
