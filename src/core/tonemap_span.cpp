// Highway kernel of tonemapSpan (color.h), compiled per x86 target and dispatched at run time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "core/tonemap_span.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
//
#include <hwy/contrib/math/math-inl.h>
#include <hwy/highway.h>

#include <algorithm>

#include "core/color.h"

HWY_BEFORE_NAMESPACE();
namespace tandem {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Every value is one channel: the curve and the sRGB encoding act per channel, so an RGB row
// is a flat span.
void TonemapSpanImpl(const float* in, float* out, size_t n, float ev, ToneOperator op) {
  const hn::ScalableTag<float> d;
  const size_t lanes = hn::Lanes(d);
  const auto zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const auto scale = hn::Set(d, std::exp2(ev));  // hoisted: one exp2 per span
  HWY_ALIGN float tail[HWY_MAX_BYTES / sizeof(float)];
  for (size_t i = 0; i < n; i += lanes) {
    // Plain loads and stores for whole vectors; the span's tail goes through a vector-sized
    // copy. (Highway 1.0's masked load and blended store on SSE4 access the whole vector:
    // an aligned load of an unaligned tail, and a read-modify-write past the span, which
    // belongs to the next tile and another thread.)
    const bool whole = i + lanes <= n;
    const float* src = in + i;
    if (!whole) {
      std::copy(in + i, in + n, tail);
      std::fill(tail + (n - i), tail + lanes, 0.0f);
      src = tail;
    }
    auto v = hn::Mul(hn::LoadU(d, src), scale);
    v = hn::IfThenElseZero(hn::IsFinite(v), hn::Max(v, zero));  // NaN, inf, negative -> 0
    switch (op) {
      case ToneOperator::Clamp:
        v = hn::Min(v, one);
        break;
      case ToneOperator::Reinhard:
        v = hn::Div(v, hn::Add(one, v));
        break;
      case ToneOperator::Aces: {  // Narkowicz's fit x (a x + b) / (x (c x + d) + e)
        const auto num = hn::Mul(v, hn::MulAdd(hn::Set(d, 2.51f), v, hn::Set(d, 0.03f)));
        const auto den =
            hn::MulAdd(v, hn::MulAdd(hn::Set(d, 2.43f), v, hn::Set(d, 0.59f)), hn::Set(d, 0.14f));
        v = hn::Min(hn::Max(hn::Div(num, den), zero), one);
        break;
      }
    }
    // sRGB: 12.92 c below 0.0031308, else 1.055 c^(1/2.4) - 0.055.
    const auto curve = hn::MulAdd(
        hn::Set(d, 1.055f),
        hn::Exp(d, hn::Mul(hn::Log(d, hn::Max(v, hn::Set(d, 1e-30f))), hn::Set(d, 1.0f / 2.4f))),
        hn::Set(d, -0.055f));
    const auto linear = hn::Mul(v, hn::Set(d, 12.92f));
    v = hn::IfThenElse(hn::Le(v, hn::Set(d, 0.0031308f)), linear, hn::Min(curve, one));
    if (whole) {
      hn::StoreU(v, d, out + i);
    } else {
      hn::Store(v, d, tail);
      std::copy(tail, tail + (n - i), out + i);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace tandem
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tandem {
HWY_EXPORT(TonemapSpanImpl);
void tonemapSpan(const float* in, float* out, size_t n, float ev, ToneOperator op) {
  HWY_DYNAMIC_DISPATCH(TonemapSpanImpl)(in, out, n, ev, op);
}
}  // namespace tandem
#endif
