// Barycentrics of a triangle seen from a fixed eye, from per-triangle plane equations: for a
// ray eye + t d, u = (d . Nu) / (d . Nw) and v = (d . Nv) / (d . Nw), with Nu = e2 x s,
// Nv = s x e1, Nw = e2 x e1 and s = eye - a (the triple products of Moller-Trumbore regrouped
// so that everything but d is per triangle). Three dot products and one reciprocal a pixel, and
// d need not be unit length: the raster resolve walks unnormalised pixel rays.
#pragma once
#include <cstdint>

#include "core/math.h"

namespace tandem {

struct TrianglePlanes {
  Vec3 nu, nv, nw;
  float tw;  // -(s . Nw): the ray parameter is t = tw / (d . Nw)

  static TrianglePlanes make(Vec3 eye, Vec3 a, Vec3 b, Vec3 c) {
    const Vec3 e1 = b - a, e2 = c - a, s = eye - a;
    const Vec3 nw = cross(e2, e1);
    return {cross(e2, s), cross(s, e1), nw, -dot(s, nw)};
  }
  // Barycentrics (u: vertex b, v: vertex c) and ray parameter t (in units of d) along d; false
  // when d runs parallel to the plane.
  bool barycentrics(Vec3 d, float& t, float& u, float& v) const {
    const float w = dot(d, nw);
    if (w == 0.0f) return false;
    const float r = 1.0f / w;
    t = tw * r;
    u = dot(d, nu) * r;
    v = dot(d, nv) * r;
    return true;
  }
};

// Remembers the planes of the last triangle a thread resolved: neighbouring pixels mostly see
// the same one.
struct TrianglePlaneCache {
  uint32_t object = ~0u, prim = ~0u;
  TrianglePlanes planes{};
};

}  // namespace tandem
