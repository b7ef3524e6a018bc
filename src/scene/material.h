// Tandem's material: every property of Walewski et al. 2019 Table 1 plus what glTF/OBJ need.
// Colours are linear RGB. Texture indices are -1 when absent.
#pragma once
#include <cmath>
#include <string>

#include "core/math.h"

namespace tandem {

enum class AlphaMode { Opaque, Mask, Blend };

struct Material {
  std::string name = "default";
  Vec3 emission{0, 0, 0};            // radiance emitted (W/sr/m^2), >= 0
  Vec3 ambient{1, 1, 1};             // multiplies the scene's global ambient colour
  Vec3 diffuse{0.8f, 0.8f, 0.8f};    // albedo in [0,1]
  float diffuseOpacity = 1.0f;       // Table 1 diffuse A (also glTF base-colour alpha)
  Vec3 specular{0, 0, 0};            // specular colour in [0,1]
  float specularExponent = 1.0f;     // Blinn-Phong exponent in [1, 255] (Table 1 footnote a)
  float reflectivity = 0.0f;         // optical R: mirror reflection weight in [0,1]
  float ior = 1.0f;                  // optical G: index of refraction, >= 1 typical
  float opacity = 1.0f;              // optical B: 1 opaque, 0 fully transmissive
  Vec3 transmissionFilter{1, 1, 1};  // OBJ Tf: the colour light keeps passing through
  Vec2 tiling{1, 1};                 // texture tiling (scale of UV)
  Vec2 offset{0, 0};                 // texture offset
  float uvRotation = 0.0f;           // KHR_texture_transform rotation (radians)
  bool castsShadows = true;
  bool doubleSided = false;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  int diffuseTexture = -1;   // sRGB colour texture; alpha is opacity
  int emissionTexture = -1;  // sRGB
  int specularTexture = -1;  // sRGB
  int normalTexture = -1;    // tangent-space normal map, linear
  float normalScale = 1.0f;
  // glTF metallic-roughness texture (B = metallic, G = roughness): when present, diffuse,
  // specular, exponent and reflectivity are derived per texel from these factors.
  int metallicRoughnessTexture = -1;
  // glTF occlusion (R channel): scales the ambient term only, by 1 + strength (occlusion - 1).
  int occlusionTexture = -1;
  float occlusionStrength = 1.0f;
  Vec3 baseColor{1, 1, 1};
  float metallic = 0.0f, roughness = 1.0f;

  // Maps a mesh UV to texture space: offset + R(rotation) * (uv * tiling).
  bool hasTexture() const {
    return diffuseTexture >= 0 || emissionTexture >= 0 || specularTexture >= 0 ||
           metallicRoughnessTexture >= 0 || normalTexture >= 0 || occlusionTexture >= 0;
  }
  Vec2 transformUv(Vec2 uv) const {  // inline: the raster resolve calls it every pixel
    Vec2 s = uv * tiling;
    if (uvRotation != 0.0f) {
      // KHR_texture_transform rotates counter-clockwise in UV space.
      float c = std::cos(uvRotation), n = std::sin(uvRotation);
      s = {c * s.x + n * s.y, -n * s.x + c * s.y};
    }
    return s + offset;
  }
};

// Metallic-roughness -> Blinn-Phong terms (docs/scene-format.md), used by the glTF loader for the
// factors and by surface resolve per texel.
struct BlinnPhongTerms {
  Vec3 diffuse, specular;
  float exponent, reflectivity;
};
BlinnPhongTerms fromMetallicRoughness(Vec3 base, float metallic, float roughness);

}  // namespace tandem
