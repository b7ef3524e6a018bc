#include "passes/common/vbuffer_shading.h"

#include <optional>

#include "pipeline/gbuffer_io.h"
#include "pipeline/gpu_gbuffer.h"
#include "pipeline/view_tiles.h"
#include "shading/batch_shader.h"

namespace tandem {

std::vector<BufferSlot> VBufferShadingPass::outputs() const {
  std::vector<BufferSlot> out = {{Slots::hdr, 3}};
  for (const BufferSlot& s : gbufferSlots()) out.push_back(s);
  return out;
}

void VBufferShadingPass::execute(FrameContext& ctx) {
  surfaces_.rasterize(ctx, *this);
  const auto t1 = Clock::now();
  Buffer& hdr = ctx.output(*this, Slots::hdr);
  // The G-buffer only when something reads a field of it beyond depth and ids (a pass, an AOV,
  // the viewer's shown buffer); a frame that needs only the image skips its stores.
  bool gbuffer = false;
  for (const BufferSlot& s : gbufferSlots())
    if (s.slot != "depth" && s.slot != "object_id" && ctx.isConsumed(*this, s.slot)) gbuffer = true;
  std::optional<GBufferView> g;
  Buffer *depth = nullptr, *ids = nullptr;
  if (gbuffer) {
    g = gbufferTargets(ctx, *this);
    writer_.beginFrame(ctx.frame);
  } else {
    for (const BufferSlot& s : gbufferSlots()) {
      Buffer* b = ctx.outputIfConsumed(*this, s.slot);  // drops values left from earlier frames
      if (s.slot == "depth") depth = b;
      if (s.slot == "object_id") ids = b;
    }
  }
  const Scene& scene = *ctx.scene;
  const ShadingContext shading = ShadingContext::from(scene);
  // Shading a pixel into the tile's batch, and the sky where nothing was drawn.
  struct TileShading {
    const Scene& scene;
    const View& v;
    Buffer& hdr;
    BatchShader shader;
    bool perspective = v.camera.desc.projection == Projection::Perspective;
    void shade(int x, int y, const SurfaceSample& s) {
      // The surface lies on the pixel's camera ray: the eye direction needs no ray.
      shader.batch().set(shader.lane(), s,
                         perspective ? normalize(v.camera.eye - s.position) : -v.camera.forward);
      shader.push(x, y);
    }
    void sky(int x, int y) {
      Vec3 o, d;
      v.jitteredCamera.generateRay(float(x - v.x) + 0.5f, float(y - v.y) + 0.5f, o, d);
      hdr.setRgb(x, y, scene.skyRadiance(d));
    }
  };
  // Two loops, each its own function: one holding both resolves inlined less of each.
  if (g) {
    parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
      TileShading t{scene, v, hdr, BatchShader(shading, hdr)};
      writer_.tile(
          surfaces_, ctx, *g, v, x0, y0, x1, y1,
          [&](int x, int y, const SurfaceSample& s, float) { t.shade(x, y, s); },
          [&](int x, int y, Vec3) { t.sky(x, y); });
    });
  } else {
    parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
      TileShading t{scene, v, hdr, BatchShader(shading, hdr)};
      VisibleSurfaces::TriangleCache cache;
      surfaces_.resolveTile(
          ctx, v, x0, y0, x1, y1, cache,
          [&](int x, int y, const SurfaceSample& s, float d, Vec2) {
            if (depth) depth->at(x, y)[0] = d;
            if (ids) ids->at(x, y)[0] = float(s.object);
            t.shade(x, y, s);
          },
          [&](int x, int y, Vec3) {
            t.sky(x, y);
            if (depth) depth->at(x, y)[0] = 0.0f;
            if (ids) ids->at(x, y)[0] = -1.0f;
          });
    });
  }
  ctx.passParts.push_back({"shading", msSince(t1), 0});
}

// On the GPU each G-buffer target is written only when something reads it (the CPU writes them
// all once one is read): the image and every target read are the same.
void VBufferShadingPass::executeGpu(FrameContext& ctx) {
  const uint64_t hdr = ctx.deviceOutput(*this, Slots::hdr);
  gpuSurfaces_.record(ctx, *this, gbufferDeviceTargetsIfConsumed(ctx, *this), hdr, "shading",
                      settings().gpuRasterizer == RasterizerSettings::GpuRasterizer::Graphics);
}

}  // namespace tandem
