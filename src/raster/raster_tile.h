// The rasterizer's inner loop for one 64x64 tile, vectorised with Highway: a triangle's pixel
// box is walked a few pixels at a time, edge functions in exact 64-bit lanes (the same integers,
// the same top-left rule as the scalar loop), depth and the ids in 32-bit lanes. The result is
// bit for bit the scalar loop's (this file is built without FMA contraction; the pixel's depth
// is the plane's value at the pixel, zRow + dzdx * k, in both).
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "raster/rasterizer.h"

namespace tandem {

struct RasterTile {
  float* depth;
  uint32_t* object;
  uint32_t* prim;
  int width;           // row stride of the three buffers
  int x0, y0, x1, y1;  // the tile, inclusive
};

// A triangle's pixel box inside a tile and its edge functions there: E_e(px, py) =
// rowE[e] + stepX[e] (px - px0) + stepY[e] (py - py0), >= 0 inside (edge e runs from vertex e to
// e + 1; positive orientation; top-left rule by a bias of -1 on the edges a triangle does not
// own, so a pixel centre on an edge shared by two triangles belongs to exactly one).
struct TriangleBox {
  int px0, px1, py0, py1;
  int64_t rowE[3], stepX[3], stepY[3];
  bool empty() const { return px0 > px1 || py0 > py1; }
};
inline TriangleBox triangleBox(const Rasterizer::SetupTriangle& t, int x0, int y0, int x1, int y1) {
  constexpr int kSubBits = kRasterSubBits;
  TriangleBox b;
  const int32_t minX = std::min({t.x[0], t.x[1], t.x[2]}),
                maxX = std::max({t.x[0], t.x[1], t.x[2]});
  const int32_t minY = std::min({t.y[0], t.y[1], t.y[2]}),
                maxY = std::max({t.y[0], t.y[1], t.y[2]});
  b.px0 = std::max(x0, int((minX - 128 + 255) >> kSubBits));
  b.px1 = std::min(x1, int((maxX - 128) >> kSubBits));
  b.py0 = std::max(y0, int((minY - 128 + 255) >> kSubBits));
  b.py1 = std::min(y1, int((maxY - 128) >> kSubBits));
  if (b.empty()) return b;
  const int64_t sx = (int64_t(b.px0) << kSubBits) + 128, sy = (int64_t(b.py0) << kSubBits) + 128;
  for (int e = 0; e < 3; ++e) {
    const int a = e, c = (e + 1) % 3;
    const int64_t dx = int64_t(t.x[c]) - t.x[a], dy = int64_t(t.y[c]) - t.y[a];
    const bool owns = dy < 0 || (dy == 0 && dx > 0);
    b.rowE[e] = dx * (sy - t.y[a]) - dy * (sx - t.x[a]) + (owns ? 0 : -1);
    b.stepX[e] = -dy * 256;
    b.stepY[e] = dx * 256;
  }
  return b;
}

// Depth at the centre of pixel (px0, py) of the box: the plane z = zRef + dzdx (x - xRef) +
// dzdy (y - yRef); a pixel k to the right adds dzdx k (not summed pixel by pixel).
inline float rowDepth(const Rasterizer::SetupTriangle& t, const TriangleBox& b, int py) {
  return t.zRef + t.dzdy * (py + 0.5f - t.yRef) + t.dzdx * (b.px0 + 0.5f - t.xRef);
}

// row(py, e) for each row of the box, e the edge values at its first pixel.
template <class Row>
inline void walkRows(const TriangleBox& b, Row&& row) {
  int64_t e[3] = {b.rowE[0], b.rowE[1], b.rowE[2]};
  for (int py = b.py0; py <= b.py1; ++py) {
    row(py, e);
    for (int k = 0; k < 3; ++k) e[k] += b.stepY[k];
  }
}

// visit(px, z) for each covered pixel of [px, b.px1] in one row, from the edge values e at px
// and the row's depth zRow: the pixel-by-pixel walk.
template <class Visit>
inline void walkRowPixels(const Rasterizer::SetupTriangle& t, const TriangleBox& b, int px,
                          const int64_t e[3], float zRow, Visit&& visit) {
  int64_t e0 = e[0], e1 = e[1], e2 = e[2];
  for (; px <= b.px1; ++px) {
    if ((e0 | e1 | e2) >= 0) visit(px, zRow + t.dzdx * float(px - b.px0));
    e0 += b.stepX[0];
    e1 += b.stepX[1];
    e2 += b.stepX[2];
  }
}

// Rasterizes tris[ids[i]] for i in [first, n) in order into `tile`, stopping before the first
// alpha-masked triangle (the caller tests its texels, then resumes after it). Returns the index
// it stopped at (n when all were drawn).
size_t rasterTileTriangles(const RasterTile& tile, const Rasterizer::SetupTriangle* tris,
                           const uint32_t* ids, size_t first, size_t n);

}  // namespace tandem
