#include "scene/material.h"

#include <cmath>

namespace tandem {

Vec2 Material::transformUv(Vec2 uv) const {
  Vec2 s = uv * tiling;
  if (uvRotation != 0.0f) {
    // KHR_texture_transform rotates counter-clockwise in UV space.
    float c = std::cos(uvRotation), n = std::sin(uvRotation);
    s = {c * s.x + n * s.y, -n * s.x + c * s.y};
  }
  return s + offset;
}

}  // namespace tandem
