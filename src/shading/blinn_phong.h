// The one shading function (seed 002 Listing 5): emission + global ambient x ambient + the sum
// over every directional, point and spot light of Blinn-Phong diffuse and specular terms, with
// distance attenuation and spot-cone falloff. Used by deferred shading and by every ray hit.
//
// Units: the diffuse term carries the Lambertian 1/pi and the specular lobe is the normalised
// Blinn-Phong (n + 8) / (8 pi), so light intensities are physical and later path-traced
// references agree with raster shading of directly lit surfaces.
#pragma once
#include "scene/light.h"
#include "shading/surface.h"

namespace tandem {

struct Scene;

struct LightSample {
  Vec3 wi;         // unit direction from the surface towards the light
  float distance;  // to the light (infinity for directional)
  Vec3 radiance;   // irradiance-at-normal-incidence factor: colour x intensity x attenuation
};

// Incident light from one light at point p (no visibility test).
LightSample sampleLight(const Light& l, Vec3 p);

// Reflected radiance towards wo (unit, surface -> viewer). lightVisibility, when given, holds one
// factor in [0,1] per scene light (shadow rays of later passes); null means fully visible.
Vec3 shadeBlinnPhong(const SurfaceSample& s, Vec3 wo, const Scene& scene,
                     const float* lightVisibility = nullptr);

}  // namespace tandem
