// Textures: RGBA texels kept as 8-bit mip chains (colour textures sRGB-encoded and decoded on
// sample through a 256-entry table; normal maps linear), filtered bilinearly within a level and
// linearly between levels (trilinear) by a level of detail the caller derives from the pixel's
// texture footprint; glTF sampler wrap modes. `texels` keeps the linear float level 0 for export
// and hashing.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/buffer.h"
#include "core/math.h"

namespace tandem {

enum class WrapMode { Repeat, ClampToEdge, MirroredRepeat };

struct Texture {
  std::string name;  // file path or generator name, for `info`
  Buffer texels;     // RGBA, linear, level 0
  WrapMode wrapS = WrapMode::Repeat, wrapT = WrapMode::Repeat;
  bool srgb = true;  // levels store sRGB-encoded colour (false: values as stored, normal maps)

  struct Level {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
  };
  std::vector<Level> levels;  // 8-bit mip chain, level 0 first (built by buildLevels)

  // Bilinear at level 0; v = 0 at the top row (glTF convention).
  Vec4 sample(Vec2 uv) const { return sample(uv, 0.0f); }
  // Trilinear at level of detail `lod` (0: full resolution; clamped to the chain).
  Vec4 sample(Vec2 uv, float lod) const;
  // Level of detail for a footprint of `uvPerPixel` texture-space units per pixel.
  float lodFor(float uvPerPixel) const;
  // (Re)builds `levels` from `texels`: box-filtered in linear space, stored in 8 bits.
  void buildLevels();
};

// Makes an RGBA texture from 8-bit file data; `srgb` decodes colour to linear.
Texture textureFromImage(std::string name, Buffer rgba, bool srgb);
// A procedural checkerboard (linear colours), `cells` squares per side.
Texture checkerTexture(int size, int cells, Vec3 a, Vec3 b);

}  // namespace tandem
