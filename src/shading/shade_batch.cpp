// Highway kernel of shade_batch.h, compiled for each x86 target and dispatched at run time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "shading/shade_batch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
//
#include <hwy/contrib/math/math-inl.h>
#include <hwy/highway.h>

#include "shading/shade_batch.h"

HWY_BEFORE_NAMESPACE();
namespace tandem {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// 1/sqrt(x) from the hardware estimate and one Newton step (relative error ~1e-7).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V Rsqrt(D d, V x) {
  const V r = hn::ApproximateReciprocalSqrt(x);
  const V half_x_r2 = hn::Mul(hn::Mul(hn::Set(d, 0.5f), x), hn::Mul(r, r));
  return hn::Mul(r, hn::Sub(hn::Set(d, 1.5f), half_x_r2));
}

// x^e for x in [0, 1] and e >= 0 (0^e = 0 for e > 0, x^0 = 1), inline and branch-free.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V Pow01(D d, V x, V e) {
  const V lx = hn::Log(d, hn::Max(x, hn::Set(d, 1e-30f)));
  return hn::Exp(d, hn::Mul(e, lx));
}

template <class V>
HWY_INLINE V Dot(V ax, V ay, V az, V bx, V by, V bz) {
  return hn::MulAdd(ax, bx, hn::MulAdd(ay, by, hn::Mul(az, bz)));
}

// Over whole vectors of D; a batch of one runs on a one-lane tag (scalar cost, same code).
// perLight (optional): each light's unshadowed luminance per lane at perLight[li * plStride +
// lane], zeroed by the caller; terms (optional): its kLightTerms terms (shade_batch.h) at
// terms[(kLightTerms * li + t) * plStride + lane], zeroed by the caller.
template <class D>
void ShadeLanes(D d, ShadeBatch& b, const ShadingContext& ctx, const float* vis, size_t visStride,
                float* perLight = nullptr, size_t plStride = 0, float* terms = nullptr) {
  using F = ShadeBatch;
  using V = hn::Vec<D>;
  const size_t n = hn::Lanes(d);
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  for (size_t i = 0; i < size_t(b.count); i += n) {
    const auto live = hn::FirstN(d, size_t(b.count) - i);
    auto load = [&](int field) { return hn::MaskedLoad(live, d, b.f[field] + i); };
    const V px = load(F::PX), py = load(F::PY), pz = load(F::PZ);
    const V nx = load(F::NX), ny = load(F::NY), nz = load(F::NZ);
    const V wx = load(F::WX), wy = load(F::WY), wz = load(F::WZ);
    const V invPi = hn::Set(d, kInvPi);
    const V dr = hn::Mul(load(F::DR), invPi), dg = hn::Mul(load(F::DG), invPi),
            db = hn::Mul(load(F::DB), invPi);
    const V ex = load(F::EXP);
    // Normalised Blinn-Phong: (n + 8) / (8 pi).
    const V specNorm = hn::Mul(hn::Add(ex, hn::Set(d, 8.0f)), hn::Set(d, 1.0f / (8.0f * kPi)));
    const V sr = hn::Mul(load(F::SR), specNorm), sg = hn::Mul(load(F::SG), specNorm),
            sb = hn::Mul(load(F::SB), specNorm);
    V cr = hn::MulAdd(hn::Set(d, ctx.ambient.x), load(F::AR), load(F::ER));
    V cg = hn::MulAdd(hn::Set(d, ctx.ambient.y), load(F::AG), load(F::EG));
    V cb = hn::MulAdd(hn::Set(d, ctx.ambient.z), load(F::AB), load(F::EB));
    // Early outs taken only when every lane agrees (a single ray hit always does): no specular
    // lobe, a light fully occluded, or facing away.
    const bool anySpecular = !hn::AllTrue(d, hn::Eq(hn::Add(hn::Add(sr, sg), sb), zero));
    const size_t lightCount = b.lights ? b.lightCount : ctx.lights.size();
    for (size_t n = 0; n < lightCount; ++n) {
      const size_t li = b.lights ? b.lights[n] : n;
      const PreparedLight& l = ctx.lights[li];
      V visR = one, visG = one, visB = one;
      if (vis) {
        const float* row = vis + 3 * li * visStride + i;
        visR = hn::MaskedLoad(live, d, row);
        visG = hn::MaskedLoad(live, d, row + visStride);
        visB = hn::MaskedLoad(live, d, row + 2 * visStride);
        if (hn::AllTrue(d, hn::Le(hn::Max(hn::Max(visR, visG), visB), zero))) continue;
      }
      V lx, ly, lz, att;  // unit direction towards the light, attenuation
      if (l.type == LightType::Directional) {
        lx = hn::Set(d, -l.direction.x), ly = hn::Set(d, -l.direction.y);
        lz = hn::Set(d, -l.direction.z);
        att = one;
      } else {
        const V dx = hn::Sub(hn::Set(d, l.position.x), px);
        const V dy = hn::Sub(hn::Set(d, l.position.y), py);
        const V dz = hn::Sub(hn::Set(d, l.position.z), pz);
        const V dist2 = hn::Max(Dot(dx, dy, dz, dx, dy, dz), hn::Set(d, 1e-30f));
        const V inv = Rsqrt(d, dist2);
        const V dist = hn::Mul(dist2, inv);
        lx = hn::Mul(dx, inv), ly = hn::Mul(dy, inv), lz = hn::Mul(dz, inv);
        const V denom =
            hn::MulAdd(hn::Set(d, l.attQuadratic), dist2,
                       hn::MulAdd(hn::Set(d, l.attLinear), dist, hn::Set(d, l.attConstant)));
        att = hn::Div(one, hn::Max(denom, hn::Set(d, 1e-8f)));
        if (l.range > 0) att = hn::IfThenZeroElse(hn::Gt(dist, hn::Set(d, l.range)), att);
        if (l.type == LightType::Spot) {
          const V cosT = hn::Neg(Dot(lx, ly, lz, hn::Set(d, l.direction.x),
                                     hn::Set(d, l.direction.y), hn::Set(d, l.direction.z)));
          V cone;
          if (l.hemisphere) {
            cone = hn::IfThenElseZero(hn::Gt(cosT, zero), one);
          } else if (l.cosInner <= l.cosOuter) {
            cone = hn::IfThenElseZero(hn::Ge(cosT, hn::Set(d, l.cosOuter)), one);
          } else {  // smoothstep(cosOuter, cosInner, cosT)
            const V t = hn::Min(hn::Max(hn::Mul(hn::Sub(cosT, hn::Set(d, l.cosOuter)),
                                                hn::Set(d, 1.0f / (l.cosInner - l.cosOuter))),
                                        zero),
                                one);
            cone = hn::Mul(hn::Mul(t, t), hn::NegMulAdd(hn::Set(d, 2.0f), t, hn::Set(d, 3.0f)));
          }
          if (l.cosinePower > 0)
            cone = hn::Mul(cone, Pow01(d, hn::Max(cosT, zero), hn::Set(d, l.cosinePower)));
          att = hn::Mul(att, cone);
        }
      }
      const V nDotL = Dot(nx, ny, nz, lx, ly, lz);
      const V k = hn::IfThenElseZero(hn::Gt(nDotL, zero), hn::Mul(att, nDotL));
      if (hn::AllTrue(d, hn::Le(k, zero))) continue;
      V lobe = zero;
      if (anySpecular) {
        // Half vector (a zero sum stays zero, as normalize() leaves it).
        const V hx = hn::Add(lx, wx), hy = hn::Add(ly, wy), hz = hn::Add(lz, wz);
        const V hInv = Rsqrt(d, hn::Max(Dot(hx, hy, hz, hx, hy, hz), hn::Set(d, 1e-30f)));
        const V nDotH = hn::Max(hn::Mul(Dot(nx, ny, nz, hx, hy, hz), hInv), zero);
        lobe = Pow01(d, nDotH, ex);
      }
      if (perLight) {
        const V base = hn::Mul(
            k, hn::MulAdd(
                   hn::Set(d, 0.2126f * l.power.x), hn::MulAdd(sr, lobe, dr),
                   hn::MulAdd(hn::Set(d, 0.7152f * l.power.y), hn::MulAdd(sg, lobe, dg),
                              hn::Mul(hn::Set(d, 0.0722f * l.power.z), hn::MulAdd(sb, lobe, db)))));
        hn::BlendedStore(base, live, d, perLight + li * plStride + i);
      }
      const V pr = hn::Mul(k, hn::Set(d, l.power.x)), pg = hn::Mul(k, hn::Set(d, l.power.y)),
              pb = hn::Mul(k, hn::Set(d, l.power.z));
      const V xr = hn::MulAdd(sr, lobe, dr), xg = hn::MulAdd(sg, lobe, dg),
              xb = hn::MulAdd(sb, lobe, db);
      if (terms) {
        float* t = terms + kLightTerms * li * plStride + i;
        hn::BlendedStore(xr, live, d, t);
        hn::BlendedStore(xg, live, d, t + plStride);
        hn::BlendedStore(xb, live, d, t + 2 * plStride);
        hn::BlendedStore(pr, live, d, t + 3 * plStride);
        hn::BlendedStore(pg, live, d, t + 4 * plStride);
        hn::BlendedStore(pb, live, d, t + 5 * plStride);
      }
      cr = hn::MulAdd(xr, hn::Mul(pr, visR), cr);
      cg = hn::MulAdd(xg, hn::Mul(pg, visG), cg);
      cb = hn::MulAdd(xb, hn::Mul(pb, visB), cb);
    }
    hn::BlendedStore(cr, live, d, b.f[F::OR] + i);
    hn::BlendedStore(cg, live, d, b.f[F::OG] + i);
    hn::BlendedStore(cb, live, d, b.f[F::OB] + i);
  }
}

// shadeBatch's sum from the terms lightContributions kept: the same products added in the same
// order, so the same result to the bit, without evaluating a light again.
template <class D>
void ShadeTermsLanes(D d, ShadeBatch& b, const ShadingContext& ctx, const float* terms,
                     const float* vis, size_t stride) {
  using F = ShadeBatch;
  using V = hn::Vec<D>;
  const size_t n = hn::Lanes(d);
  const V zero = hn::Zero(d);
  for (size_t i = 0; i < size_t(b.count); i += n) {
    const auto live = hn::FirstN(d, size_t(b.count) - i);
    auto load = [&](const float* p) { return hn::MaskedLoad(live, d, p); };
    V cr = hn::MulAdd(hn::Set(d, ctx.ambient.x), load(b.f[F::AR] + i), load(b.f[F::ER] + i));
    V cg = hn::MulAdd(hn::Set(d, ctx.ambient.y), load(b.f[F::AG] + i), load(b.f[F::EG] + i));
    V cb = hn::MulAdd(hn::Set(d, ctx.ambient.z), load(b.f[F::AB] + i), load(b.f[F::EB] + i));
    const size_t lightCount = b.lights ? b.lightCount : ctx.lights.size();
    for (size_t k = 0; k < lightCount; ++k) {
      const size_t li = b.lights ? b.lights[k] : k;
      const float* row = vis + 3 * li * stride + i;
      const V visR = load(row), visG = load(row + stride), visB = load(row + 2 * stride);
      if (hn::AllTrue(d, hn::Le(hn::Max(hn::Max(visR, visG), visB), zero))) continue;
      const float* t = terms + kLightTerms * li * stride + i;
      cr = hn::MulAdd(load(t), hn::Mul(load(t + 3 * stride), visR), cr);
      cg = hn::MulAdd(load(t + stride), hn::Mul(load(t + 4 * stride), visG), cg);
      cb = hn::MulAdd(load(t + 2 * stride), hn::Mul(load(t + 5 * stride), visB), cb);
    }
    hn::BlendedStore(cr, live, d, b.f[F::OR] + i);
    hn::BlendedStore(cg, live, d, b.f[F::OG] + i);
    hn::BlendedStore(cb, live, d, b.f[F::OB] + i);
  }
}

void ShadeTermsImpl(ShadeBatch& b, const ShadingContext& ctx, const float* terms, const float* vis,
                    size_t stride) {
  if (b.count == 1)
    ShadeTermsLanes(hn::CappedTag<float, 1>(), b, ctx, terms, vis, stride);
  else
    ShadeTermsLanes(hn::ScalableTag<float>(), b, ctx, terms, vis, stride);
}

void ShadeBatchImpl(ShadeBatch& b, const ShadingContext& ctx, const float* vis, size_t visStride) {
  if (b.count == 1)
    ShadeLanes(hn::CappedTag<float, 1>(), b, ctx, vis, visStride);
  else
    ShadeLanes(hn::ScalableTag<float>(), b, ctx, vis, visStride);
}

void LightContributionsImpl(ShadeBatch& b, const ShadingContext& ctx, float* perLight,
                            size_t stride, float* terms) {
  if (b.count == 1)
    ShadeLanes(hn::CappedTag<float, 1>(), b, ctx, nullptr, 0, perLight, stride, terms);
  else
    ShadeLanes(hn::ScalableTag<float>(), b, ctx, nullptr, 0, perLight, stride, terms);
}

}  // namespace HWY_NAMESPACE
}  // namespace tandem
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <algorithm>
#include <cmath>

#include "shading/light_cull_grid.h"

namespace tandem {

HWY_EXPORT(ShadeBatchImpl);
HWY_EXPORT(LightContributionsImpl);
HWY_EXPORT(ShadeTermsImpl);

void lightContributions(ShadeBatch& b, const ShadingContext& ctx, float* perLight, size_t stride,
                        float* terms) {
  const size_t lights = b.lights ? b.lightCount : ctx.lights.size();
  for (size_t n = 0; n < lights; ++n) {
    const size_t li = b.lights ? b.lights[n] : n;
    std::fill(perLight + li * stride, perLight + li * stride + size_t(b.count), 0.0f);
    if (terms)
      for (size_t t = 0; t < size_t(kLightTerms); ++t) {
        float* row = terms + (kLightTerms * li + t) * stride;
        std::fill(row, row + size_t(b.count), 0.0f);
      }
  }
  HWY_DYNAMIC_DISPATCH(LightContributionsImpl)(b, ctx, perLight, stride, terms);
}

void shadeFromTerms(ShadeBatch& b, const ShadingContext& ctx, const float* terms,
                    const float* lightVisibility, size_t stride) {
  HWY_DYNAMIC_DISPATCH(ShadeTermsImpl)(b, ctx, terms, lightVisibility, stride);
}

void shadeBatch(ShadeBatch& b, const ShadingContext& ctx, const float* lightVisibility,
                size_t visStride) {
  HWY_DYNAMIC_DISPATCH(ShadeBatchImpl)(b, ctx, lightVisibility, visStride);
}

void lightsReaching(const ShadingContext& ctx, const Bounds3& box, std::vector<uint32_t>& out) {
  thread_local std::vector<uint32_t> near;
  if (ctx.cull) ctx.cull->candidates(box, near);
  const size_t count = ctx.cull ? near.size() : ctx.lights.size();
  out.clear();
  const Vec3 centre = (box.lo + box.hi) * 0.5f;
  const float radius = 0.5f * length(box.hi - box.lo);
  for (size_t n = 0; n < count; ++n) {
    const size_t i = ctx.cull ? near[n] : n;
    const PreparedLight& l = ctx.lights[i];
    bool reaches = true;
    // (Only a range or a spot cone can leave a light out.)
    if (l.type != LightType::Directional && (l.range > 0 || l.type == LightType::Spot)) {
      const Vec3 v = centre - l.position;
      const float dist = length(v);
      if (l.range > 0 && dist > l.range + radius) reaches = false;
      // Spot: the box's bounding sphere must overlap the outer cone (smoothstep is 0 outside).
      if (reaches && l.type == LightType::Spot && !l.hemisphere && dist > radius) {
        const float angle = std::acos(std::clamp(dot(v, l.direction) / dist, -1.0f, 1.0f));
        reaches = angle <= l.outerAngle + std::asin(std::min(radius / dist, 1.0f)) + 1e-4f;
      }
    }
    if (reaches) out.push_back(uint32_t(i));
  }
}

void cullLights(ShadeBatch& b, const ShadingContext& ctx, std::vector<uint32_t>& out,
                const Bounds3* lanes) {
  Bounds3 box;
  using F = ShadeBatch;
  if (lanes)
    box = *lanes;
  else
    for (int k = 0; k < b.count; ++k) box.extend(Vec3(b.f[F::PX][k], b.f[F::PY][k], b.f[F::PZ][k]));
  lightsReaching(ctx, box, out);
  b.lights = out.data();
  b.lightCount = out.size();
}

}  // namespace tandem
#endif
