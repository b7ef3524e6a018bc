// The one shading function (Walewski et al. 2019 Listing 5): emission + global ambient x ambient +
// the sum over every directional, point and spot light of Blinn-Phong diffuse and specular terms,
// with distance attenuation and spot-cone falloff. Used by deferred shading and by every ray hit.
//
// Units: the diffuse term carries the Lambertian 1/pi and the specular lobe is the normalised
// Blinn-Phong (n + 8) / (8 pi), so light intensities are physical and later path-traced
// references agree with raster shading of directly lit surfaces.
#pragma once
#include <memory>
#include <vector>

#include "scene/light.h"
#include "shading/surface.h"

namespace tandem {

struct Scene;
class LightCullGrid;

struct LightSample {
  Vec3 wi;         // unit direction from the surface towards the light
  float distance;  // to the light (infinity for directional)
  Vec3 radiance;   // irradiance-at-normal-incidence factor: colour x intensity x attenuation
};

// A light with everything that does not depend on the shaded point worked out once per frame
// (power, cone cosines), so no trigonometry runs per pixel.
struct PreparedLight {
  LightType type;
  Vec3 power;  // colour x intensity
  Vec3 position, direction;
  float attConstant, attLinear, attQuadratic, range;
  float cosOuter, cosInner, cosinePower;
  float outerAngle;  // acos(cosOuter) in radians, for light culling
  bool hemisphere;   // spot with both cones at 90 degrees: a hard cut at the plane
  static PreparedLight from(const Light& l);
};

// What shading needs from the scene, prepared once per frame and shared by every pixel/hit.
struct ShadingContext {
  Vec3 ambient{0, 0, 0};
  std::vector<PreparedLight> lights;  // same order as Scene::lights
  // Which lights reach where, for scenes of many range-limited lights (null otherwise): shading
  // then visits the lights that reach a point, not all of them (lightsReaching, shade_batch.h).
  std::shared_ptr<const LightCullGrid> cull;
  static ShadingContext from(const Scene& scene);
};

// Incident light from one light at point p (no visibility test).
LightSample sampleLight(const PreparedLight& l, Vec3 p);
inline LightSample sampleLight(const Light& l, Vec3 p) {
  return sampleLight(PreparedLight::from(l), p);
}

// Reflected radiance towards wo (unit, surface -> viewer). lightVisibility, when given, holds an
// RGB transmittance in [0,1] per scene light (shadow rays); null means fully visible.
Vec3 shadeBlinnPhong(const SurfaceSample& s, Vec3 wo, const ShadingContext& ctx,
                     const Vec3* lightVisibility = nullptr);
// Convenience for one-off evaluations (tests): prepares the context from the scene each call.
Vec3 shadeBlinnPhong(const SurfaceSample& s, Vec3 wo, const Scene& scene,
                     const Vec3* lightVisibility = nullptr);

}  // namespace tandem
