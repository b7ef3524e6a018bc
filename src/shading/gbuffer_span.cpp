// Highway kernel of GBufferReader::readSpan: a run of pixels of one row loaded from the
// interleaved G-buffer targets straight into a shading batch's lanes (deinterleaved in vectors
// instead of lane by lane), with the eye directions. Built without FMA contraction: the eye
// direction rounds as normalize() does, so the batch is bit-identical to read() lane by lane.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "shading/gbuffer_span.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
//
#include <hwy/highway.h>

#include "shading/gbuffer_layout.h"
#include "shading/gbuffer_sample.h"
#include "shading/shade_batch.h"

HWY_BEFORE_NAMESPACE();
namespace tandem {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

bool ReadSpanImpl(const GBufferReader::Planes& g, size_t i0, size_t n, ShadeBatch& b,
                  bool perspective, Vec3 eye, Bounds3& bounds) {
  using F = ShadeBatch;
  const hn::ScalableTag<float> d;
  const size_t lanes = hn::Lanes(d);
  const auto zero = hn::Zero(d);
  // Background anywhere: the caller takes the pixels one by one.
  auto background = hn::Lt(hn::LoadU(d, g.objectId + i0), zero);
  for (size_t i = lanes; i < n; i += lanes)
    background = hn::Or(background, hn::Lt(hn::LoadU(d, g.objectId + i0 + i), zero));
  if (!hn::AllFalse(d, background)) return false;
  auto lo = hn::Set(d, g.position[3 * i0]), hi = lo;  // per axis: x, y, z
  auto loY = hn::Set(d, g.position[3 * i0 + 1]), hiY = loY;
  auto loZ = hn::Set(d, g.position[3 * i0 + 2]), hiZ = loZ;
  for (size_t i = 0; i < n; i += lanes) {
    const size_t p = i0 + i;
    hn::Vec<decltype(d)> a, c, e, w;
    auto put3 = [&](int field) {
      hn::Store(a, d, b.f[field] + i);
      hn::Store(c, d, b.f[field + 1] + i);
      hn::Store(e, d, b.f[field + 2] + i);
    };
    hn::LoadInterleaved3(d, g.position + 3 * p, a, c, e);
    put3(F::PX);
    lo = hn::Min(lo, a), hi = hn::Max(hi, a);
    loY = hn::Min(loY, c), hiY = hn::Max(hiY, c);
    loZ = hn::Min(loZ, e), hiZ = hn::Max(hiZ, e);
    if (perspective) {  // normalize(eye - p): ((x x + y y) + z z), then a division by the root
      const auto vx = hn::Sub(hn::Set(d, eye.x), a), vy = hn::Sub(hn::Set(d, eye.y), c),
                 vz = hn::Sub(hn::Set(d, eye.z), e);
      const auto l2 = hn::Add(hn::Add(hn::Mul(vx, vx), hn::Mul(vy, vy)), hn::Mul(vz, vz));
      const auto len = hn::Sqrt(l2);
      const auto valid = hn::Gt(l2, zero);
      a = hn::IfThenElseZero(valid, hn::Div(vx, len));
      c = hn::IfThenElseZero(valid, hn::Div(vy, len));
      e = hn::IfThenElseZero(valid, hn::Div(vz, len));
    } else {
      a = hn::Set(d, eye.x), c = hn::Set(d, eye.y), e = hn::Set(d, eye.z);
    }
    put3(F::WX);
    hn::LoadInterleaved3(d, g.normal + 3 * p, a, c, e);
    put3(F::NX);
    // Interleaved loads: rgb then the fourth channel (gbuffer_layout.h).
    static_assert(DiffuseChannels::kRgb == 0 && DiffuseChannels::kCount == 4 &&
                  SpecularChannels::kRgb == 0 && SpecularChannels::kExponent == 3 &&
                  SpecularChannels::kCount == 4);
    hn::LoadInterleaved4(d, g.diffuse + 4 * p, a, c, e, w);
    put3(F::DR);
    hn::LoadInterleaved4(d, g.specular + 4 * p, a, c, e, w);
    put3(F::SR);
    hn::Store(w, d, b.f[F::EXP] + i);
    hn::LoadInterleaved3(d, g.emission + 3 * p, a, c, e);
    put3(F::ER);
    hn::LoadInterleaved3(d, g.ambient + 3 * p, a, c, e);
    put3(F::AR);
  }
  bounds.lo = {hn::GetLane(hn::MinOfLanes(d, lo)), hn::GetLane(hn::MinOfLanes(d, loY)),
               hn::GetLane(hn::MinOfLanes(d, loZ))};
  bounds.hi = {hn::GetLane(hn::MaxOfLanes(d, hi)), hn::GetLane(hn::MaxOfLanes(d, hiY)),
               hn::GetLane(hn::MaxOfLanes(d, hiZ))};
  return true;
}

}  // namespace HWY_NAMESPACE
}  // namespace tandem
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tandem {
HWY_EXPORT(ReadSpanImpl);

bool GBufferReader::readSpan(int x, int y, int n, ShadeBatch& b, bool perspective, Vec3 eye,
                             Bounds3& bounds) const {
  const size_t i = size_t(y) * size_t(width_) + size_t(x);
  return HWY_DYNAMIC_DISPATCH(ReadSpanImpl)(g_, i, size_t(n), b, perspective, eye, bounds);
}

}  // namespace tandem
#endif
