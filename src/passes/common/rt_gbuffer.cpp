#include "passes/common/rt_gbuffer.h"

#include <tbb/enumerable_thread_specific.h>

#include <atomic>

#include "gpu/shaders/rt_gbuffer_spv.h"
#include "pipeline/gbuffer_io.h"
#include "pipeline/gpu_frame.h"
#include "pipeline/gpu_gbuffer.h"
#include "pipeline/view_tiles.h"
#include "rt/primary_rays.h"

#include "shading/surface_resolve.h"
#include "shading/surface_resolve_inline.h"

namespace tandem {

std::vector<BufferSlot> RTGBufferPass::outputs() const {
  return gbufferSlots();
}

void RTGBufferPass::execute(FrameContext& ctx) {
  RayTracer& rt = ctx.rayTracer();
  GBufferView g = gbufferTargets(ctx, *this);
  // Each worker's recently set-up triangles (neighbouring rays mostly hit the same ones).
  tbb::enumerable_thread_specific<TriangleSetupCache<>> caches;
  // Both eyes of a stereo frame in one parallel dispatch (Peres 2022 §5.1's single ray-generation
  // pass over the dual screen); tiles never straddle the eyes.
  std::atomic<uint64_t> rays{0};
  parallelViewTiles(ctx.views, [&](const View& v, int fx0, int fy0, int fx1, int fy1) {
    const float spread = ctx.pixelSpread(v);  // texture level of detail, as raster
    auto pixel = [&](int x, int y, const Ray& r, const Hit& h) {
      if (!h.valid()) {
        g.writeBackground(x + v.x, y + v.y,
                          g.wantsMotion() ? backgroundMotion(v, r.dir) : Vec2{0, 0});
        return;
      }
      // Embree's own distance and barycentrics: no second intersection.
      const float tuv[3] = {h.t, h.u, h.v};
      const SurfaceSample s = [&] {
        if (!ctx.frame.objects[size_t(h.object)].stepPositions.empty())
          return resolveSurface(ctx.frame, h.object, h.prim, r.origin, r.dir, r.time, tuv, spread);
        bool fresh;
        const TriangleSetup& tri =
            caches.local().get(ctx.frame, uint32_t(h.object), uint32_t(h.prim), fresh).setup;
        return resolveSurfaceInline(tri, r.origin, r.dir, tuv, spread);
      }();
      const float depth = g.wantsDepth() ? v.jitteredCamera.depthOf(r.origin + r.dir * h.t) : 0.0f;
      g.write(x + v.x, y + v.y, s, depth,
              g.wantsMotion() ? motionVector(ctx.frame, v, s.object, s.position) : Vec2{0, 0});
    };
    rays +=
        tracePrimaryTile(v.jitteredCamera, rt, fx0 - v.x, fy0 - v.y, fx1 - v.x, fy1 - v.y,
                         [&](int n, const int* px, const int* py, const Ray* rs, const Hit* hits) {
                           for (int k = 0; k < n; ++k) pixel(px[k], py[k], rs[k], hits[k]);
                         });
  });
  ctx.passRays += double(rays.load());
}

void RTGBufferPass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  GBufferArgs a{};
  a.scene = gpu.scene(ctx.frame).sceneAddress();
  a.targets = gbufferDeviceTargets(ctx, *this);
  a.motion = gpuObjectMotionConstants(ctx);
  a.frameWidth = ctx.width;
  const GpuKernel& k =
      gpu.kernel("rt_gbuffer", kRtGbufferSpv, sizeof(kRtGbufferSpv) / 4, sizeof(GBufferArgs));
  double rays = 0;
  for (const View& v : ctx.views) {
    a.view = gpuViewConstants(ctx, v);
    a.viewX = v.x;
    a.viewY = v.y;
    gpu.dispatchInterruptibly(k, uint32_t(v.width() + 7) / 8, uint32_t(v.height() + 7) / 8, &a);
    rays += double(v.width()) * double(v.height());
  }
  ctx.passRays += rays;  // one camera ray a pixel
}

}  // namespace tandem
