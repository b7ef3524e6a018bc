// Highway kernel of raster_tile.h, compiled for each x86 target and dispatched once per tile
// and chunk of triangles.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "raster/raster_tile.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
//
#include <hwy/highway.h>

#include "raster/raster_tile.h"

HWY_BEFORE_NAMESPACE();
namespace tandem {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The depth test and write of one covered pixel: what the vector lanes do, for the tail of a row.
HWY_INLINE void DrawPixel(const RasterTile& tile, size_t i, float z, uint32_t object,
                          uint32_t prim) {
  if (z > tile.depth[i] && z <= 1.0f) {
    tile.depth[i] = z;
    tile.object[i] = object;
    tile.prim[i] = prim;
  }
}

size_t RasterTileTrianglesImpl(const RasterTile& tile, const Rasterizer::SetupTriangle* tris,
                               const uint32_t* ids, size_t first, size_t n) {
  const hn::ScalableTag<int64_t> d64;         // edge functions: exact 64-bit integers
  const hn::Rebind<float, decltype(d64)> df;  // depth, as many lanes
  const hn::Rebind<int32_t, decltype(d64)> di;
  const hn::Rebind<uint32_t, decltype(d64)> du;
  const int lanes = int(hn::Lanes(d64));
  const auto laneIndex = hn::ConvertTo(df, hn::Iota(di, 0));  // 0, 1, 2, ... (once: Iota
                                                              // goes through the stack)
  HWY_ALIGN int64_t laneSteps[3][HWY_MAX_BYTES / sizeof(int64_t)];
  for (size_t k = first; k < n; ++k) {
    const Rasterizer::SetupTriangle& t = tris[ids[k]];
    if (t.alphaMask) return k;
    const TriangleBox b = triangleBox(t, tile.x0, tile.y0, tile.x1, tile.y1);
    if (b.empty()) continue;
    const auto objectV = hn::Set(du, t.object), primV = hn::Set(du, t.prim);
    const auto oneV = hn::Set(df, 1.0f), dzdxV = hn::Set(df, t.dzdx);
    for (int e = 0; e < 3; ++e)
      for (int l = 0; l < lanes; ++l) laneSteps[e][l] = b.stepX[e] * l;
    const auto step0 = hn::Load(d64, laneSteps[0]), step1 = hn::Load(d64, laneSteps[1]),
               step2 = hn::Load(d64, laneSteps[2]);
    // Whole windows of `lanes` pixels, then the row's tail pixel by pixel. (Measured: sliding a
    // last, partly masked window inside the tile instead of the scalar tail was slower, since
    // most rows of the atrium's triangles are shorter than a window.)
    // Rows walked here, not through walkRows: the vector body inside walkRows' lambda measured
    // 1.7x slower.
    int64_t rowE[3] = {b.rowE[0], b.rowE[1], b.rowE[2]};
    for (int py = b.py0; py <= b.py1; ++py) {
      const size_t row = size_t(py) * size_t(tile.width);
      const float zRow = rowDepth(t, b, py);
      const auto zRowV = hn::Set(df, zRow);
      int64_t e[3] = {rowE[0], rowE[1], rowE[2]};
      int px = b.px0;
      for (; px + lanes - 1 <= b.px1; px += lanes) {
        const auto inside =
            hn::Or(hn::Or(hn::Add(hn::Set(d64, e[0]), step0), hn::Add(hn::Set(d64, e[1]), step1)),
                   hn::Add(hn::Set(d64, e[2]), step2));
        const auto covered = hn::Not(hn::Lt(inside, hn::Zero(d64)));
        e[0] += b.stepX[0] * lanes;
        e[1] += b.stepX[1] * lanes;
        e[2] += b.stepX[2] * lanes;
        if (hn::AllFalse(d64, covered)) continue;
        uint8_t bits[8] = {};
        hn::StoreMaskBits(d64, covered, bits);
        const auto mf = hn::LoadMaskBits(df, bits);
        const size_t i = row + size_t(px);
        // k + lane as a float: exact (small integers), so the same value as float(px - px0).
        const auto k = hn::Add(hn::Set(df, float(px - b.px0)), laneIndex);
        const auto z = hn::Add(zRowV, hn::Mul(dzdxV, k));
        const auto depth = hn::LoadU(df, tile.depth + i);
        const auto pass = hn::And(mf, hn::And(hn::Gt(z, depth), hn::Le(z, oneV)));
        hn::BlendedStore(z, pass, df, tile.depth + i);
        const auto passU = hn::RebindMask(du, pass);
        hn::BlendedStore(objectV, passU, du, tile.object + i);
        hn::BlendedStore(primV, passU, du, tile.prim + i);
      }
      // The row's tail (shorter than a window) pixel by pixel.
      walkRowPixels(t, b, px, e, zRow,
                    [&](int x, float z) { DrawPixel(tile, row + size_t(x), z, t.object, t.prim); });
      rowE[0] += b.stepY[0];
      rowE[1] += b.stepY[1];
      rowE[2] += b.stepY[2];
    }
  }
  return n;
}

}  // namespace HWY_NAMESPACE
}  // namespace tandem
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tandem {

HWY_EXPORT(RasterTileTrianglesImpl);

size_t rasterTileTriangles(const RasterTile& tile, const Rasterizer::SetupTriangle* tris,
                           const uint32_t* ids, size_t first, size_t n) {
  return HWY_DYNAMIC_DISPATCH(RasterTileTrianglesImpl)(tile, tris, ids, first, n);
}

}  // namespace tandem
#endif
