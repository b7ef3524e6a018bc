// The surface record: what a rasterized pixel and a ray hit both know about the point they see.
// The G-buffer stores exactly these fields, and shading reads only these, so raster and ray
// tracing cannot be told apart by the shading code.
#pragma once
#include "core/math.h"

namespace tandem {

struct SurfaceSample {
  Vec3 position;   // world space
  Vec3 normal;     // shading normal (normal map applied), unit
  Vec3 geoNormal;  // geometric normal, unit
  Vec2 uv;         // texture-space UV (material tiling/offset applied)
  Vec3 emission{0, 0, 0};
  Vec3 ambient{0, 0, 0};
  Vec3 diffuse{0, 0, 0};
  float diffuseOpacity = 1.0f;
  Vec3 specular{0, 0, 0};
  float specularExponent = 1.0f;
  float reflectivity = 0.0f, ior = 1.0f, opacity = 1.0f;  // optical properties (Table 1)
  int object = -1, material = -1;
  float t = 0.0f;  // distance along the ray that found it
};

}  // namespace tandem
