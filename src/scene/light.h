// Punctual lights. Units: point/spot intensity in W/sr, directional irradiance in W/m^2,
// both times `color`. No fixed limit on the count.
#pragma once
#include <string>

#include "core/math.h"

namespace tandem {

enum class LightType { Directional, Point, Spot };

struct Light {
  LightType type = LightType::Point;
  std::string name;
  Vec3 color{1, 1, 1};
  float intensity = 1.0f;
  Vec3 position{0, 0, 0};    // point, spot
  Vec3 direction{0, -1, 0};  // directional, spot: the direction light travels (unit)
  // Distance attenuation 1 / (c + l d + q d^2); the default is physical inverse square.
  float attConstant = 0.0f, attLinear = 0.0f, attQuadratic = 1.0f;
  float range = 0.0f;  // > 0: light has no effect beyond this distance
  float innerConeDeg = 30.0f, outerConeDeg = 45.0f;  // spot: full intensity inside inner
  float cosinePower = 0.0f;  // spot: extra cos^n(theta) falloff (1 for an emissive quad)
  bool castsShadows = true;
  // Stands in for an emissive mesh (loaders.h): a path tracer, which sees the mesh's emission
  // itself, must not count it twice.
  bool fromEmissiveMesh = false;
};

}  // namespace tandem
