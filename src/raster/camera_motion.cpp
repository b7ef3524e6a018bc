// Highway kernel of camera_motion.h, compiled for each x86 target and dispatched per tile.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "raster/camera_motion.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
//
#include <hwy/highway.h>

#include "raster/camera_motion.h"
#include "raster/gbuffer.h"

HWY_BEFORE_NAMESPACE();
namespace tandem {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Row r of the matrix against (x, y, z, 1), component by component in projectToPixel's order.
template <class V>
HWY_INLINE V DotRow(V m0, V m1, V m2, V m3, V x, V y, V z, V one) {
  return hn::Add(hn::Add(hn::Add(hn::Mul(m0, x), hn::Mul(m1, y)), hn::Mul(m2, z)),
                 hn::Mul(m3, one));
}

void WriteCameraMotionImpl(const CameraMotionTile& tile, const View& view, const float* moved,
                           int objects) {
  if (objects <= 0) return;
  bool anyMoved = false;  // else no pixel needs its object's flag looked up
  for (int o = 0; o < objects; ++o) anyMoved = anyMoved || moved[o] != 0.0f;
  const hn::ScalableTag<float> d;
  const hn::RebindToSigned<decltype(d)> di;
  const int lanes = int(hn::Lanes(d));
  const Camera& prev = view.prevCamera;
  const float* m = &prev.viewProjUnjittered.m[0][0];
  const auto m0 = hn::Set(d, m[0]), m1 = hn::Set(d, m[1]), m2 = hn::Set(d, m[2]),
             m3 = hn::Set(d, m[3]);
  const auto m4 = hn::Set(d, m[4]), m5 = hn::Set(d, m[5]), m6 = hn::Set(d, m[6]),
             m7 = hn::Set(d, m[7]);
  const auto m12 = hn::Set(d, m[12]), m13 = hn::Set(d, m[13]), m14 = hn::Set(d, m[14]),
             m15 = hn::Set(d, m[15]);
  const auto one = hn::Set(d, 1.0f);
  const auto half = hn::Set(d, 0.5f), eps = hn::Set(d, 1e-8f);
  const auto width = hn::Set(d, float(prev.width)), height = hn::Set(d, float(prev.height));
  const auto laneIndex = hn::ConvertTo(d, hn::Iota(di, 0));
  const auto jx = hn::Set(d, view.jitter.x);
  const auto objectsV = hn::Set(di, objects);
  for (int y = tile.y0; y < tile.y1; ++y) {
    const size_t row = size_t(y) * size_t(tile.stride);
    const float pyPlus = (float(y - view.y) + 0.5f) + view.jitter.y;  // pixel.y + jitter.y
    const auto pyV = hn::Set(d, pyPlus);
    int x = tile.x0;
    for (; x + lanes <= tile.x1; x += lanes) {
      const size_t i = row + size_t(x);
      const auto id = hn::ConvertTo(di, hn::LoadU(d, tile.objectId + i));
      const auto valid = hn::And(hn::Not(hn::Lt(id, hn::Zero(di))), hn::Lt(id, objectsV));
      const auto safe = hn::IfThenElseZero(valid, id);
      const auto still = anyMoved ? hn::And(hn::RebindMask(d, valid),
                                            hn::Eq(hn::GatherIndex(d, moved, safe), hn::Zero(d)))
                                  : hn::RebindMask(d, valid);
      if (hn::AllFalse(d, still)) continue;
      hn::Vec<decltype(d)> px, py, pz;
      hn::LoadInterleaved3(d, tile.position + 3 * i, px, py, pz);
      const auto hx = DotRow(m0, m1, m2, m3, px, py, pz, one);
      const auto hy = DotRow(m4, m5, m6, m7, px, py, pz, one);
      const auto hw = DotRow(m12, m13, m14, m15, px, py, pz, one);
      const auto inFront = hn::Gt(hw, eps);
      const auto safeW = hn::IfThenElse(inFront, hw, one);
      const auto bx = hn::Mul(hn::Add(hn::Mul(hn::Div(hx, safeW), half), half), width);
      const auto by = hn::Mul(hn::Sub(half, hn::Mul(hn::Div(hy, safeW), half)), height);
      // pixel + jitter - before, pixel = (lx + 0.5, ly + 0.5); behind the camera: 0.
      const auto pxPlus =
          hn::Add(hn::Add(hn::Add(hn::Set(d, float(x - view.x)), laneIndex), half), jx);
      const auto mvx = hn::IfThenElseZero(inFront, hn::Sub(pxPlus, bx));
      const auto mvy = hn::IfThenElseZero(inFront, hn::Sub(pyV, by));
      // Interleave into the two-channel buffer, keeping the lanes of moved objects and sky.
      if (hn::AllTrue(d, still)) {
        hn::StoreInterleaved2(mvx, mvy, d, tile.motion + 2 * i);
        continue;
      }
      hn::Vec<decltype(d)> ox, oy;
      hn::LoadInterleaved2(d, tile.motion + 2 * i, ox, oy);
      hn::StoreInterleaved2(hn::IfThenElse(still, mvx, ox), hn::IfThenElse(still, mvy, oy), d,
                            tile.motion + 2 * i);
    }
    for (; x < tile.x1; ++x) {  // the row's tail, as the scalar resolve computes it
      const size_t i = row + size_t(x);
      const int id = int(tile.objectId[i]);
      if (id < 0 || id >= objects || moved[id] != 0.0f) continue;
      const float* p = tile.position + 3 * i;
      const Vec2 mv = reprojectedMotion(view, Vec3(p[0], p[1], p[2]),
                                        Vec2{float(x - view.x) + 0.5f, float(y - view.y) + 0.5f});
      tile.motion[2 * i] = mv.x;
      tile.motion[2 * i + 1] = mv.y;
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace tandem
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tandem {

HWY_EXPORT(WriteCameraMotionImpl);

void writeCameraMotion(const CameraMotionTile& tile, const View& view, const float* moved,
                       int objects) {
  HWY_DYNAMIC_DISPATCH(WriteCameraMotionImpl)(tile, view, moved, objects);
}

}  // namespace tandem
#endif
