#include "passes/raster_gbuffer.h"

#include "pipeline/gbuffer_io.h"
#include "pipeline/view_tiles.h"
#include "raster/triangle_planes.h"
#include "shading/surface_resolve.h"
#include "shading/surface_resolve_inline.h"

namespace tandem {

std::vector<BufferSlot> RasterGBufferPass::outputs() const {
  return gbufferSlots();
}

void RasterGBufferPass::execute(FrameContext& ctx) {
  auto t0 = Clock::now();
  visibility_.resize(ctx.views.size());
  stats_ = {};
  for (size_t i = 0; i < ctx.views.size(); ++i) {
    RasterStats s;
    rasterizer_.render(ctx.frame, ctx.views[i].camera, visibility_[i], &s);
    stats_.trianglesIn += s.trianglesIn;
    stats_.trianglesCulled += s.trianglesCulled;
    stats_.trianglesClipped += s.trianglesClipped;
    stats_.trianglesBinned += s.trianglesBinned;
  }
  ctx.counters["raster/triangles_in"] = double(stats_.trianglesIn);
  ctx.counters["raster/triangles_culled"] = double(stats_.trianglesCulled);
  ctx.counters["raster/triangles_clipped"] = double(stats_.trianglesClipped);
  ctx.counters["raster/triangles_binned"] = double(stats_.trianglesBinned);
  ctx.passParts.push_back({"visibility", msSince(t0), 0});
  auto t1 = Clock::now();
  GBufferView g = gbufferTargets(ctx, *this);
  const FrameScene& fs = ctx.frame;
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    const VisibilityBuffer& vis = visibility_[size_t(&v - ctx.views.data())];
    const Camera& cam = v.camera;
    const bool perspective = cam.desc.projection == Projection::Perspective;
    // Triangles set up for this tile (planes and resolve constants), direct-mapped: a triangle
    // mostly covers neighbouring pixels in this row and the rows below.
    struct CachedTriangle {
      uint32_t object = ~0u, prim = ~0u;
      TrianglePlanes planes{};
      TriangleSetup setup;
    };
    constexpr size_t kCacheSize = 64;
    std::vector<CachedTriangle> cache(kCacheSize);
    const float spread = ctx.pixelSpread(v);  // texture level of detail: the pixel's cone
    for (int y = y0; y < y1; ++y) {
      const int ly = y - v.y;
      // The pixel ray (unnormalised): the row's part once, the column's a multiply-add.
      Vec3 o, dRow;
      cam.generateRayUnnormalized(-cam.jitter.x, float(ly) + 0.5f, o, dRow);  // NDC x = -1
      dRow = dRow + cam.right * cam.tanHalfFov * cam.aspect;                  // NDC x = 0
      const float ndcPerPixel = 2.0f / float(cam.width) * cam.tanHalfFov * cam.aspect;
      for (int x = x0; x < x1; ++x) {
        const int lx = x - v.x;
        size_t i = size_t(ly) * size_t(vis.width) + size_t(lx);
        Vec3 d = dRow + cam.right * ((float(lx) + 0.5f + cam.jitter.x) * ndcPerPixel -
                                     cam.tanHalfFov * cam.aspect);
        if (!perspective) cam.generateRay(float(lx) + 0.5f, float(ly) + 0.5f, o, d);
        if (vis.object[i] == kNoObject) {
          g.writeBackground(x, y, backgroundMotion(v, normalize(d)));
          continue;
        }
        const uint32_t object = vis.object[i], prim = vis.prim[i];
        // Barycentrics of the pixel's camera ray against the visible triangle: exact and
        // perspective-correct, what a primary ray would compute.
        // Initialised in place (no copy): a copied sample's position would be read back
        // before its stores retire.
        const SurfaceSample s = [&] {
          if (!fs.objects[object].stepPositions.empty())
            return resolveSurface(fs, int(object), int(prim), o, d, 0.0f, nullptr, spread);
          CachedTriangle& c = cache[(prim * 0x9E3779B1u + object) % kCacheSize];
          if (c.object != object || c.prim != prim) {
            c.object = object;
            c.prim = prim;
            c.setup = TriangleSetup::make(fs, int(object), int(prim), 0.0f);
            c.planes = TrianglePlanes::make(o, c.setup.p[0], c.setup.p[1], c.setup.p[2]);
          }
          float tuv[3] = {0, 0, 0};
          const bool planar = perspective && c.planes.barycentrics(d, tuv[1], tuv[2]);
          return resolveSurfaceInline(c.setup, o, d, planar ? tuv : nullptr, spread);
        }();
        const Vec2 pixel{float(lx) + 0.5f, float(ly) + 0.5f};
        g.write(x, y, s, vis.depth[i], motionVectorAtPixel(fs, v, s.object, s.position, pixel));
      }
    }
  });
  ctx.passParts.push_back({"resolve", msSince(t1), 0});
}

}  // namespace tandem
