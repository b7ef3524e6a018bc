#include "rt/whitted.h"

#include <cmath>
#include <limits>

#include "scene/scene.h"
#include "shading/shade_batch.h"
#include "shading/surface_resolve.h"

namespace tandem {

Vec3 combineEffects(float om, float orr, Vec3 m, Vec3 r, Vec3 c) {
  Vec3 cm = m * om + (r * orr + c * (1.0f - orr)) * (1.0f - om);
  Vec3 cr = r * orr + (m * om + c * (1.0f - om)) * (1.0f - orr);
  return (cm + cr) * 0.5f;
}

Vec3 reflectDir(Vec3 d, Vec3 n) {
  return d - n * (2.0f * dot(d, n));
}

bool refractDir(Vec3 d, Vec3 n, float eta, Vec3& out) {
  float cosi = -dot(d, n);
  float k = 1.0f - eta * eta * (1.0f - cosi * cosi);
  if (k < 0.0f) return false;
  out = normalize(d * eta + n * (eta * cosi - std::sqrt(k)));
  return true;
}

Vec3 offsetRayOrigin(const SurfaceSample& s, Vec3 dir) {
  float eps = 1e-4f * (1.0f + maxComponent(vmax(s.position, -s.position)));
  return s.position + s.geoNormal * (dot(dir, s.geoNormal) > 0 ? eps : -eps);
}

Ray shadowRayTowards(const SurfaceSample& s, const LightSample& ls, float time) {
  Ray r;
  r.origin = offsetRayOrigin(s, ls.wi);
  r.dir = ls.wi;
  r.tfar = std::isinf(ls.distance) ? std::numeric_limits<float>::infinity()
                                   : ls.distance * (1.0f - 1e-4f);
  r.time = time;
  return r;
}

bool Whitted::shadowRay(const SurfaceSample& s, size_t light, Ray& r) const {
  if (!scene_.lights[light].castsShadows) return false;
  LightSample ls = sampleLight(shading_.lights[light], s.position);
  if (dot(s.normal, ls.wi) <= 0.0f || maxComponent(ls.radiance) <= 0.0f)
    return false;  // unlit anyway
  r = shadowRayTowards(s, ls, time_);
  return true;
}

void Whitted::lightVisibility(const SurfaceSample& s, Vec3* vis) const {
  for (size_t i = 0; i < scene_.lights.size(); ++i) {
    vis[i] = Vec3(1.0f);
    Ray r;
    if (shadowRay(s, i, r)) vis[i] = rt_.transmittance(r, settings_.texturedShadows);
  }
}

Vec3 Whitted::reflectionFrom(const SurfaceSample& s, Vec3 d, int depth, float importance) const {
  Vec3 n = dot(s.normal, d) > 0 ? -s.normal : s.normal;
  Vec3 dir = normalize(reflectDir(d, n));
  return traceSecondary(offsetRayOrigin(s, dir), dir, depth, importance);
}

Vec3 Whitted::refractionFrom(const SurfaceSample& s, Vec3 d, int depth, float importance) const {
  // Entering through the front face: environment -> material; leaving: material -> environment.
  bool entering = dot(s.geoNormal, d) < 0;
  Vec3 n = dot(s.normal, d) > 0 ? -s.normal : s.normal;
  float eta = entering ? scene_.environmentIor / s.ior : s.ior / scene_.environmentIor;
  Vec3 dir;
  if (!refractDir(d, n, eta, dir)) dir = normalize(reflectDir(d, n));  // total internal reflection
  const Vec3 filter =
      s.material >= 0 ? scene_.materials[size_t(s.material)].transmissionFilter : Vec3(1.0f);
  return traceSecondary(offsetRayOrigin(s, dir), dir, depth, importance) * filter;
}

Vec3 Whitted::primaryReflection(const SurfaceSample& s, Vec3 d) const {
  return s.reflectivity > 0 ? reflectionFrom(s, d, 1, s.reflectivity) : Vec3(0.0f);
}

Vec3 Whitted::primaryRefraction(const SurfaceSample& s, Vec3 d) const {
  float transparency = 1.0f - s.opacity;
  return transparency > 0 ? refractionFrom(s, d, 1, transparency) : Vec3(0.0f);
}

Vec3 Whitted::traceSecondary(Vec3 origin, Vec3 dir, int depth, float importance) const {
  Ray r;
  r.origin = origin;
  r.dir = dir;
  r.time = time_;
  Hit h = rt_.intersect(r);
  if (!h.valid()) return scene_.skyRadiance(dir);  // Listing 8d
  const float tuv[3] = {h.t, h.u, h.v};            // Embree's own hit: no second intersection
  SurfaceSample s = resolveSurface(*rt_.frame(), h.object, h.prim, origin, dir, time_, tuv);
  const float om = s.reflectivity, orr = 1.0f - s.opacity;
  // Listing 8c: lighting only where the surface is not purely a mirror or clear glass.
  Vec3 lighting(0.0f);
  if (om < 1.0f && orr < 1.0f) lighting = shadeBlinnPhong(s, -dir, shading_);
  Vec3 refl(0.0f), refr(0.0f);
  if (depth >= settings_.maxDepth) {
    // Out of depth: the surface's own lighting stands in for further bounces (Listing 8c: none
    // on a pure mirror or clear glass, unless shade_at_max_depth asks for Blinn-Phong there).
    if (settings_.shadeAtMaxDepth) lighting = shadeBlinnPhong(s, -dir, shading_);
    refl = refr = lighting;
  } else {
    if (importance * om > settings_.importanceCutoff)
      refl = reflectionFrom(s, dir, depth + 1, importance * om);
    if (importance * orr > settings_.importanceCutoff)
      refr = refractionFrom(s, dir, depth + 1, importance * orr);
  }
  return combineEffects(om, orr, refl, refr, lighting);
}

Vec3 Whitted::shadePrimary(const SurfaceSample& s, Vec3 d) const {
  Vec3 out;
  shadePrimary8(&s, &d, 1, &out);
  return out;
}

ShadowCounts sum(ShadowTally& t) {
  ShadowCounts c;
  t.combine_each([&](const ShadowCounts& x) { c.add(x); });
  return c;
}

void Whitted::lightVisibility8(const SurfaceSample* s, int n, float* vis, int* rays, const Vec3* wo,
                               uint8_t* classes, std::vector<uint32_t>* reached) const {
  constexpr int W = 8;
  for (int k = 0; k < W; ++k)
    if (rays) rays[k] = 0;
  // The lights that may reach a lane: the others are culled without a look (and written as
  // such when the caller reads every light's row).
  thread_local std::vector<uint32_t> own;
  std::vector<uint32_t>& list = reached ? *reached : own;
  Bounds3 box;
  for (int k = 0; k < n; ++k) box.extend(s[k].position);
  lightsReaching(shading_, box, list);
  const size_t lights = list.size();
  if (classes) std::fill(classes, classes + W * scene_.lights.size(), uint8_t(ShadowClass::Culled));
  if (!reached)
    for (size_t i = 0; i < 3 * W * scene_.lights.size(); ++i) vis[i] = 1.0f;
  const ShadowMode mode = maps_ ? settings_.shadows : ShadowMode::Rays;
  // Culling by share: each light's unshadowed luminance (one SIMD shading of the lanes) against
  // the surface's unshadowed total. A light adding nothing (facing away, out of its cone or
  // range) needs no query at all. Without wo, or with every shadow traced and no threshold, the
  // per-light test of shadowRay alone decides.
  const bool shares = wo && n > 0 && (settings_.shadowCull > 0 || mode != ShadowMode::Rays);
  LightVisibility8 share(shares ? scene_.lights.size() : 0);
  float floor[W] = {};
  if (shares) {
    ShadeBatch b;
    b.count = n;
    for (int k = 0; k < n; ++k) b.set(k, s[k], wo[k]);
    b.lights = list.data();
    b.lightCount = list.size();
    lightContributions(b, shading_, share.data(), W);
    for (int k = 0; k < n; ++k) floor[k] = settings_.shadowCull * luminance(b.result(k));
  }
  ShadowCounts counts;
  counts.surfaces = uint64_t(n);
  counts.culled += uint64_t(n) * (scene_.lights.size() - lights);
  Vec3 pos[W], geo[W];
  int self[W];
  if (mode == ShadowMode::Classified)
    for (int k = 0; k < n; ++k)
      pos[k] = s[k].position, geo[k] = s[k].geoNormal, self[k] = s[k].object;
  for (size_t li = 0; li < lights; ++li) {
    const size_t i = list[li];
    Ray r[W];
    bool active[W] = {};
    Vec3 t[W];
    for (int k = 0; k < W; ++k) t[k] = Vec3(1.0f);
    bool any = false;
    const bool casts = scene_.lights[i].castsShadows;
    // The lanes the light reaches by enough to ask about (all of them without shares).
    bool asked[W] = {};
    ShadowClass cls[W];
    for (int k = 0; k < n; ++k) {
      cls[k] = ShadowClass::Culled;
      if (!shares) continue;
      const float sh = share.data()[i * W + size_t(k)];
      asked[k] = casts && sh > 0.0f && sh >= floor[k];
      if (asked[k]) cls[k] = ShadowClass::Traced;
    }
    if (shares && mode == ShadowMode::Classified) maps_->classify(i, n, pos, geo, self, asked, cls);
    for (int k = 0; k < n; ++k) {
      ShadowClass c = cls[k];
      if (!shares) {
        if (shadowRay(s[k], i, r[k])) c = ShadowClass::Traced;
      } else if (asked[k]) {
        if (c == ShadowClass::Shadowed) t[k] = Vec3(0.0f);
        if (mode == ShadowMode::Maps) {
          const float v = maps_->visibility(i, s[k].position, s[k].geoNormal);
          t[k] = Vec3(v);
          c = v > 0.5f ? ShadowClass::Lit : ShadowClass::Shadowed;
        }
        if (c == ShadowClass::Traced && !shadowRay(s[k], i, r[k])) c = ShadowClass::Culled;
      }
      active[k] = c == ShadowClass::Traced;
      any |= active[k];
      if (rays && active[k]) ++rays[k];
      if (classes) classes[i * W + size_t(k)] = uint8_t(c);
      counts.culled += c == ShadowClass::Culled;
      counts.lit += c == ShadowClass::Lit;
      counts.shadowed += c == ShadowClass::Shadowed;
      counts.traced += c == ShadowClass::Traced;
    }
    if (any) rt_.transmittance8(r, active, t, settings_.texturedShadows);
    for (int k = 0; k < W; ++k) {
      vis[(3 * i + 0) * W + size_t(k)] = t[k].x;
      vis[(3 * i + 1) * W + size_t(k)] = t[k].y;
      vis[(3 * i + 2) * W + size_t(k)] = t[k].z;
    }
  }
  if (tally_) tally_->local().add(counts);
}

void Whitted::shadePrimary8(const SurfaceSample* s, const Vec3* d, int n, Vec3* out) const {
  if (n <= 0) return;
  LightVisibility8 vis(scene_.lights.size());
  Vec3 wo[8];
  for (int k = 0; k < n; ++k) wo[k] = -d[k];
  thread_local std::vector<uint32_t> reached;
  lightVisibility8(s, n, vis.data(), nullptr, wo, nullptr, &reached);
  ShadeBatch b;
  b.count = n;
  for (int k = 0; k < n; ++k) b.set(k, s[k], -d[k]);
  b.lights = reached.data();
  b.lightCount = reached.size();
  shadeBatch(b, shading_, vis.data(), 8);
  for (int k = 0; k < n; ++k)
    out[k] = combineEffects(s[k].reflectivity, 1.0f - s[k].opacity, primaryReflection(s[k], d[k]),
                            primaryRefraction(s[k], d[k]), b.result(k));
}

}  // namespace tandem
