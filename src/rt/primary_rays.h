// Camera rays for every pixel, traced in 8-wide Embree packets over 4x2 pixel blocks,
// tile-parallel. Rays start at the near plane (where the rasterizer clips) and cull back faces of
// single-sided materials (as the rasterizer does), so ray-traced and rasterized visibility agree.
#pragma once
#include <atomic>

#include "core/parallel.h"
#include "rt/ray_tracer.h"
#include "scene/camera.h"

namespace tandem {

// Camera rays of the pixels [x0, x1) x [y0, y1) of `cam`, in 8-wide packets over 4x2 blocks:
// body(n, px, py, rays, hits) once per block of n <= 8 pixels. Returns the rays traced. `tau`:
// the shutter fraction the rays see moving objects at (the camera may also look through a lens
// point: Camera::make's `lens`).
template <class Body>
uint64_t tracePrimaryTile(const Camera& cam, const RayTracer& rt, int x0, int y0, int x1, int y1,
                          Body&& body, float tau = 0.0f) {
  uint64_t traced = 0;
  for (int by = y0; by < y1; by += 2)
    for (int bx = x0; bx < x1; bx += 4) {
      Ray rs[8];
      int px[8], py[8], n = 0;
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 4; ++i) {
          int x = bx + i, y = by + j;
          if (x >= x1 || y >= y1) continue;
          cam.generateRay(x + 0.5f, y + 0.5f, rs[n].origin, rs[n].dir);
          float cosAxis = dot(rs[n].dir, cam.forward);
          rs[n].tnear = cam.desc.projection == Projection::Perspective
                            ? cam.desc.nearPlane / std::max(cosAxis, 1e-6f)
                            : cam.desc.nearPlane;
          rs[n].time = tau;
          px[n] = x;
          py[n] = y;
          ++n;
        }
      Hit hits[8];
      rt.intersect8(rs, n, hits, /*cullBackfaces=*/true);
      traced += uint64_t(n);
      body(n, px, py, rs, hits);
    }
  return traced;
}

// Every pixel of `cam`, tile-parallel (body called from worker threads).
template <class Body>
uint64_t tracePrimaryBlocks(const Camera& cam, const RayTracer& rt, Body&& body, float tau = 0.0f) {
  std::atomic<uint64_t> rays{0};
  parallelTiles(cam.width, cam.height, [&](int x0, int y0, int x1, int y1) {
    rays += tracePrimaryTile(cam, rt, x0, y0, x1, y1, body, tau);
  });
  return rays.load();
}

// body(x, y, ray, hit) once per pixel.
template <class Body>
uint64_t tracePrimaryRays(const Camera& cam, const RayTracer& rt, Body&& body, float tau = 0.0f) {
  return tracePrimaryBlocks(
      cam, rt,
      [&](int n, const int* px, const int* py, const Ray* rs, const Hit* hits) {
        for (int k = 0; k < n; ++k) body(px[k], py[k], rs[k], hits[k]);
      },
      tau);
}

}  // namespace tandem
