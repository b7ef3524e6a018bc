// Highway kernel of shadow_lookup.h, compiled for each x86 target and dispatched at run time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "raster/shadow_lookup.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
//
#include <hwy/highway.h>

#include "raster/shadow_lookup.h"

HWY_BEFORE_NAMESPACE();
namespace tandem {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The same arithmetic as ShadowMaps::visibility, lane by lane.
void ShadowLookupImpl(const ShadowFace& f, const float* px, const float* py, const float* pz,
                      const float* nx, const float* ny, const float* nz, const float* use, size_t n,
                      float* out) {
  const hn::ScalableTag<float> d;
  const hn::RebindToSigned<decltype(d)> di;
  using V = hn::Vec<decltype(d)>;
  const size_t lanes = hn::Lanes(d);
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f), half = hn::Set(d, 0.5f);
  const V ex = hn::Set(d, f.eye.x), ey = hn::Set(d, f.eye.y), ez = hn::Set(d, f.eye.z);
  const V fx = hn::Set(d, f.forward.x), fy = hn::Set(d, f.forward.y), fz = hn::Set(d, f.forward.z);
  const V texelScale = hn::Set(d, f.texelPerDistance);
  const V w = hn::Set(d, float(f.width)), h = hn::Set(d, float(f.height));
  const auto wMax = hn::Set(di, f.width - 1), hMax = hn::Set(di, f.height - 1);
  const auto izero = hn::Zero(di), ione = hn::Set(di, 1), width = hn::Set(di, f.width);
  auto row = [&](int r, V x, V y, V z) {
    return hn::Add(
        hn::Add(hn::Add(hn::Mul(hn::Set(d, f.row[r][0]), x), hn::Mul(hn::Set(d, f.row[r][1]), y)),
                hn::Mul(hn::Set(d, f.row[r][2]), z)),
        hn::Set(d, f.row[r][3]));
  };
  for (size_t i = 0; i < n; i += lanes) {
    const auto live = hn::FirstN(d, n - i);
    auto load = [&](const float* p) { return hn::MaskedLoad(live, d, p + i); };
    const V x = load(px), y = load(py), z = load(pz);
    const auto used = hn::And(live, hn::Gt(load(use), zero));
    auto m = used;
    const V along = hn::Add(hn::Add(hn::Mul(hn::Sub(x, ex), fx), hn::Mul(hn::Sub(y, ey), fy)),
                            hn::Mul(hn::Sub(z, ez), fz));
    if (f.perspective) m = hn::AndNot(hn::Le(along, hn::Set(d, f.nearPlane)), m);
    const V texel = f.perspective ? hn::Mul(along, texelScale) : texelScale;
    const V off = hn::Mul(hn::Set(d, 1.5f), texel);
    const V qx = hn::Add(x, hn::Mul(load(nx), off)), qy = hn::Add(y, hn::Mul(load(ny), off)),
            qz = hn::Add(z, hn::Mul(load(nz), off));
    const V cw = row(2, qx, qy, qz);
    if (f.perspective) m = hn::AndNot(hn::Le(cw, hn::Set(d, 1e-8f)), m);
    const V iw = hn::Div(one, hn::IfThenElse(m, cw, one));
    const V sx = hn::Mul(hn::Add(hn::Mul(hn::Mul(row(0, qx, qy, qz), iw), half), half), w);
    const V sy = hn::Mul(hn::Sub(half, hn::Mul(hn::Mul(row(1, qx, qy, qz), iw), half)), h);
    const V fxf = hn::Floor(hn::Sub(sx, half)), fyf = hn::Floor(hn::Sub(sy, half));
    // Outside the map (and NaN) stays lit; clamp before converting so huge values stay exact.
    m = hn::And(m, hn::And(hn::Ge(fxf, hn::Set(d, -1.0f)), hn::Ge(fyf, hn::Set(d, -1.0f))));
    m = hn::And(m, hn::And(hn::Lt(fxf, w), hn::Lt(fyf, h)));
    // Used lanes outside the face are lit; unused lanes keep what the caller had (out has room
    // for whole vectors: the callers' arrays hold 16 floats).
    const V old = hn::LoadU(d, out + i);
    const V outside = hn::IfThenElse(used, one, old);
    if (hn::AllFalse(d, m)) {
      hn::StoreU(outside, d, out + i);
      continue;
    }
    const auto cx = hn::ConvertTo(di, hn::IfThenElse(m, fxf, zero));
    const auto cy = hn::ConvertTo(di, hn::IfThenElse(m, fyf, zero));
    const V dq = hn::Add(hn::Add(hn::Mul(hn::Sub(qx, ex), fx), hn::Mul(hn::Sub(qy, ey), fy)),
                         hn::Mul(hn::Sub(qz, ez), fz));
    const V bias = hn::Mul(hn::Set(d, 2.0f), texel);
    V threshold;
    if (f.perspective) {
      const V gap = hn::Sub(dq, bias);
      const auto ahead = hn::Gt(gap, zero);
      threshold =
          hn::IfThenElse(ahead, hn::Div(hn::Set(d, f.nearPlane), hn::IfThenElse(ahead, gap, one)),
                         hn::Set(d, HUGE_VALF));
    } else {
      threshold = hn::Div(hn::Sub(hn::Add(hn::Set(d, f.farPlane), bias), dq),
                          hn::Set(d, f.farPlane - f.nearPlane));
    }
    const auto x0 = hn::Min(hn::Max(cx, izero), wMax),
               x1 = hn::Min(hn::Max(hn::Add(cx, ione), izero), wMax);
    const auto y0 = hn::Min(hn::Max(cy, izero), hMax),
               y1 = hn::Min(hn::Max(hn::Add(cy, ione), izero), hMax);
    const auto r0 = hn::Mul(y0, width), r1 = hn::Mul(y1, width);
    auto tap = [&](decltype(r0) idx) {  // masked-off lanes read texel 0 (cx = cy = 0)
      const V t = hn::GatherIndex(d, f.depth, idx);
      return hn::IfThenElseZero(hn::Or(hn::Le(t, zero), hn::Le(t, threshold)), one);
    };
    const V lit = hn::Add(hn::Add(tap(hn::Add(r0, x0)), tap(hn::Add(r0, x1))),
                          hn::Add(tap(hn::Add(r1, x0)), tap(hn::Add(r1, x1))));
    hn::StoreU(hn::IfThenElse(m, hn::Mul(lit, hn::Set(d, 0.25f)), outside), d, out + i);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace tandem
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tandem {
HWY_EXPORT(ShadowLookupImpl);
void shadowLookupBatch(const ShadowFace& f, const float* px, const float* py, const float* pz,
                       const float* nx, const float* ny, const float* nz, const float* use,
                       size_t n, float* out) {
  HWY_DYNAMIC_DISPATCH(ShadowLookupImpl)(f, px, py, pz, nx, ny, nz, use, n, out);
}
}  // namespace tandem
#endif
