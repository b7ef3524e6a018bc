// The raster stage that raster_gbuffer and vbuffer_shading share: the frame's scene rasterized
// into one visibility buffer per view, then each covered pixel resolved once into a
// SurfaceSample along its camera ray (barycentrics from per-triangle planes, the triangle's
// resolve constants set up once per tile in a small direct-mapped cache).
#pragma once
#include <vector>

#include "pipeline/frame_context.h"
#include "pipeline/pass.h"
#include "raster/rasterizer.h"
#include "raster/triangle_planes.h"
#include "shading/surface_resolve.h"
#include "shading/surface_resolve_inline.h"

namespace tandem {

// The rasterizer's counters, reported by the pass that rasterizes (summed over the views).
struct RasterCounters {
  static constexpr const char* trianglesIn = "raster/triangles_in";
  static constexpr const char* trianglesCulled = "raster/triangles_culled";
  static constexpr const char* trianglesClipped = "raster/triangles_clipped";
  static constexpr const char* trianglesBinned = "raster/triangles_binned";
  static std::vector<CounterDesc> all();
};

class VisibleSurfaces {
 public:
  // Rasterizes every view; reported as `pass`'s part "visibility" and its raster/* counters.
  void rasterize(FrameContext& ctx, const Pass& pass);

  // Triangles set up for one tile, with their barycentric planes: a triangle mostly covers
  // neighbouring pixels in this row and the rows below.
  using TriangleCache = TriangleSetupCache<TrianglePlanes>;

  // Resolves the tile [x0,x1) x [y0,y1) (frame pixels) of view v row by row: surface(x, y, s,
  // depth, pixel) for covered pixels (pixel: the view-local pixel centre) and background(x, y,
  // dir) for the others (dir: the unnormalised camera ray).
  // Kept out of line: inlined into a caller's tile loop it measured 5 % slower.
  template <class Surface, class Background>
  [[gnu::noinline]] void resolveTile(const FrameContext& ctx, const View& v, int x0, int y0, int x1,
                                     int y1, TriangleCache& cache, Surface&& surface,
                                     Background&& background) const;

 private:
  Rasterizer rasterizer_;  // binning scratch reused across frames
  std::vector<VisibilityBuffer> visibility_;
};

template <class Surface, class Background>
void VisibleSurfaces::resolveTile(const FrameContext& ctx, const View& v, int x0, int y0, int x1,
                                  int y1, TriangleCache& cache, Surface&& surface,
                                  Background&& background) const {
  const VisibilityBuffer& vis = visibility_[size_t(&v - ctx.views.data())];
  const FrameScene& fs = ctx.frame;
  const Camera& cam = v.jitteredCamera;
  const bool perspective = cam.desc.projection == Projection::Perspective;
  const float spread = ctx.pixelSpread(v);  // texture level of detail: the pixel's cone
  for (int y = y0; y < y1; ++y) {
    const int ly = y - v.y;
    // The tile's row two rows down, fetched ahead: a row of a tile is a few cache lines of
    // each visibility array, too short for the hardware's stream prefetcher, and the loads of
    // the object ids stalled the loop.
    if (y + 2 < y1) {
      const size_t ahead = size_t(ly + 2) * size_t(vis.width) + size_t(x0 - v.x);
      for (int x = 0; x < x1 - x0; x += 16) {
        __builtin_prefetch(&vis.object[ahead + size_t(x)]);
        __builtin_prefetch(&vis.prim[ahead + size_t(x)]);
        __builtin_prefetch(&vis.depth[ahead + size_t(x)]);
      }
    }
    // The pixel ray (unnormalised): the row's part once, the column's a multiply-add.
    Vec3 o, dRow;
    cam.generateRayUnnormalized(-cam.jitter.x, float(ly) + 0.5f, o, dRow);  // NDC x = -1
    dRow = dRow + cam.right * cam.tanHalfFov * cam.aspect;                  // NDC x = 0
    const float ndcPerPixel = 2.0f / float(cam.width) * cam.tanHalfFov * cam.aspect;
    for (int x = x0; x < x1; ++x) {
      const int lx = x - v.x;
      const size_t i = size_t(ly) * size_t(vis.width) + size_t(lx);
      Vec3 d = dRow + cam.right * ((float(lx) + 0.5f + cam.jitter.x) * ndcPerPixel -
                                   cam.tanHalfFov * cam.aspect);
      if (!perspective) cam.generateRay(float(lx) + 0.5f, float(ly) + 0.5f, o, d);
      if (vis.object[i] == kNoObject) {
        background(x, y, d);
        continue;
      }
      const uint32_t object = vis.object[i], prim = vis.prim[i];
      // Barycentrics of the pixel's camera ray against the visible triangle: exact and
      // perspective-correct, what a primary ray would compute. Initialised in place (no copy):
      // a copied sample's fields would be read back before their stores retire.
      const SurfaceSample s = [&] {
        if (!fs.objects[object].stepPositions.empty())
          return resolveSurface(fs, int(object), int(prim), o, d, 0.0f, nullptr, spread);
        bool fresh;
        TriangleCache::Entry& c = cache.get(fs, object, prim, fresh);
        if (fresh) c.extra = TrianglePlanes::make(o, c.setup.p[0], c.setup.p[1], c.setup.p[2]);
        float tuv[3] = {0, 0, 0};
        const bool planar = perspective && c.extra.barycentrics(d, tuv[0], tuv[1], tuv[2]);
        return resolveSurfaceInline(c.setup, o, d, planar ? tuv : nullptr, spread);
      }();
      surface(x, y, s, vis.depth[i], Vec2{float(lx) + 0.5f, float(ly) + 0.5f});
    }
  }
}

}  // namespace tandem
