#include "passes/common/deferred_shading.h"

#include <algorithm>

#include "gpu/shaders/deferred_shading_spv.h"
#include "pipeline/gbuffer_io.h"
#include "pipeline/gpu_frame.h"
#include "pipeline/gpu_gbuffer.h"
#include "pipeline/view_tiles.h"
#include "shading/batch_shader.h"

namespace tandem {

std::vector<BufferSlot> DeferredShadingPass::inputs() const {
  return gbufferSampleSlots();
}

void DeferredShadingPass::execute(FrameContext& ctx) {
  const GBufferReader g = gbufferSource(ctx, *this);
  Buffer& hdr = ctx.output(*this, Slots::hdr);
  const Scene& scene = *ctx.scene;
  const ShadingContext shading = ShadingContext::from(scene);
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    const Camera& cam = v.jitteredCamera;
    const bool perspective = cam.desc.projection == Projection::Perspective;
    BatchShader shader(shading, hdr);
    ShadeBatch& b = shader.batch();
    const Vec3 eye = perspective ? cam.eye : -cam.forward;
    constexpr int kSpan = ShadeBatch::kMax;
    for (int y = y0; y < y1; ++y)
      for (int xs = x0; xs < x1; xs += kSpan) {
        const int xe = std::min(xs + kSpan, x1);
        // A run of foreground pixels fills a whole batch in vectors; runs that touch the
        // background go pixel by pixel (the partial batch before a whole run is shaded first).
        if (xe - xs == kSpan) {
          shader.flush();
          Bounds3 lanes;
          if (g.readSpan(xs, y, kSpan, b, perspective, eye, lanes)) {
            shader.pushSpan(xs, y, kSpan, lanes);
            continue;
          }
        }
        for (int x = xs; x < xe; ++x) {
          const int lane = shader.lane();
          if (!g.read(x, y, b, lane)) {
            Vec3 o, d;
            cam.generateRay(float(x - v.x) + 0.5f, float(y - v.y) + 0.5f, o, d);
            hdr.setRgb(x, y, scene.skyRadiance(d));
            continue;
          }
          // The G-buffer point lies on the pixel's camera ray: the eye direction needs no ray.
          using F = ShadeBatch;
          const Vec3 p{b.f[F::PX][lane], b.f[F::PY][lane], b.f[F::PZ][lane]};
          const Vec3 wo = perspective ? normalize(eye - p) : eye;
          b.f[F::WX][lane] = wo.x, b.f[F::WY][lane] = wo.y, b.f[F::WZ][lane] = wo.z;
          shader.push(x, y);
        }
      }
  });
}

void DeferredShadingPass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  GBufferShadeArgs a{};
  a.scene = gpu.scene(ctx.frame).sceneAddress();
  a.targets = gbufferDeviceSources(ctx, *this);
  a.hdr = ctx.deviceOutput(*this, Slots::hdr);
  a.frameWidth = ctx.width;
  const GpuKernel& k = gpu.kernel("deferred_shading", kDeferredShadingSpv,
                                  sizeof(kDeferredShadingSpv) / 4, sizeof(GBufferShadeArgs));
  for (const View& v : ctx.views) {
    a.view = gpuViewConstants(ctx, v);
    a.viewX = v.x;
    a.viewY = v.y;
    gpu.commands().dispatch(k, uint32_t(v.width() + 7) / 8, uint32_t(v.height() + 7) / 8, 1, &a);
  }
}

}  // namespace tandem
