// The resolve into the G-buffer that raster_gbuffer and vbuffer_shading share: each covered
// pixel's SurfaceSample written with its depth and motion, the background cleared, and under a
// moving camera the motion of still surfaces reprojected per tile by the vector kernel
// (raster/camera_motion.h). A caller may also do its own work on each pixel (vbuffer_shading
// shades it).
#pragma once
#include <vector>

#include "passes/common/visible_surfaces.h"
#include "raster/camera_motion.h"
#include "raster/gbuffer.h"

namespace tandem {

class GBufferWriter {
 public:
  // Once per frame, before the tiles: which objects moved since the last frame.
  void beginFrame(const FrameScene& fs) {
    moved_.resize(fs.objects.size());
    for (size_t o = 0; o < fs.objects.size(); ++o) moved_[o] = fs.objects[o].moved ? 1.0f : 0.0f;
  }

  // Resolves the tile [x0,x1) x [y0,y1) of view v into g; then also surface(x, y, s, depth) and
  // background(x, y, dir) as VisibleSurfaces::resolveTile calls them.
  template <class Surface, class Background>
  void tile(const VisibleSurfaces& surfaces, const FrameContext& ctx, GBufferView& g, const View& v,
            int x0, int y0, int x1, int y1, Surface&& surface, Background&& background) const {
    const FrameScene& fs = ctx.frame;
    VisibleSurfaces::TriangleCache cache;
    const bool motion = g.wantsMotion(), reproject = motion && v.cameraMoved;
    surfaces.resolveTile(
        ctx, v, x0, y0, x1, y1, cache,
        [&](int x, int y, const SurfaceSample& s, float depth, Vec2 pixel) {
          g.write(x, y, s, depth,
                  !motion || (reproject && !fs.objects[size_t(s.object)].moved)
                      ? Vec2{0, 0}
                      : motionVectorAtPixel(fs, v, s.object, s.position, pixel));
          surface(x, y, s, depth);
        },
        [&](int x, int y, Vec3 d) {
          g.writeBackground(x, y, motion ? backgroundMotion(v, normalize(d)) : Vec2{0, 0});
          background(x, y, d);
        });
    if (reproject)
      writeCameraMotion({g.position, g.objectId, g.motion, g.width, x0, y0, x1, y1}, v,
                        moved_.data(), int(moved_.size()));
  }

 private:
  std::vector<float> moved_;  // per object: 1 if it moved since last frame
};

}  // namespace tandem
