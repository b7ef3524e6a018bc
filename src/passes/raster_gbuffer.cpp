#include "passes/raster_gbuffer.h"

#include "pipeline/gbuffer_io.h"
#include "pipeline/view_tiles.h"
#include "raster/camera_motion.h"

namespace tandem {

std::vector<BufferSlot> RasterGBufferPass::outputs() const {
  return gbufferSlots();
}

void RasterGBufferPass::execute(FrameContext& ctx) {
  surfaces_.rasterize(ctx);
  const auto t1 = Clock::now();
  GBufferView g = gbufferTargets(ctx, *this);
  const FrameScene& fs = ctx.frame;
  // When the camera moved, the motion of everything that stood still is reprojected in vectors
  // over each resolved tile (raster/camera_motion.h); the resolve computes it only for objects
  // that moved themselves.
  moved_.resize(fs.objects.size());
  for (size_t o = 0; o < fs.objects.size(); ++o) moved_[o] = fs.objects[o].moved ? 1.0f : 0.0f;
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    VisibleSurfaces::TriangleCache cache;
    const bool motion = g.wantsMotion(), reproject = motion && v.cameraMoved;
    surfaces_.resolveTile(
        ctx, v, x0, y0, x1, y1, cache,
        [&](int x, int y, const SurfaceSample& s, float depth, Vec2 pixel) {
          g.write(x, y, s, depth,
                  !motion || (reproject && !fs.objects[size_t(s.object)].moved)
                      ? Vec2{0, 0}
                      : motionVectorAtPixel(fs, v, s.object, s.position, pixel));
        },
        [&](int x, int y, Vec3 d) {
          g.writeBackground(x, y, motion ? backgroundMotion(v, normalize(d)) : Vec2{0, 0});
        });
    if (reproject)
      writeCameraMotion({g.position, g.objectId, g.motion, g.width, x0, y0, x1, y1}, v,
                        moved_.data(), int(moved_.size()));
  });
  ctx.passParts.push_back({"resolve", msSince(t1), 0});
}

}  // namespace tandem
