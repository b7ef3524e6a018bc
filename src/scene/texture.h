// Textures: RGBA float texels in linear space (colour textures are decoded from sRGB when
// loaded; normal maps stay as stored), bilinear filtering, glTF sampler wrap modes.
#pragma once
#include <string>
#include <vector>

#include "core/buffer.h"
#include "core/math.h"

namespace tandem {

enum class WrapMode { Repeat, ClampToEdge, MirroredRepeat };

struct Texture {
  std::string name;  // file path or generator name, for `info`
  Buffer texels;     // RGBA
  WrapMode wrapS = WrapMode::Repeat, wrapT = WrapMode::Repeat;

  Vec4 sample(Vec2 uv) const;  // bilinear, v = 0 at the top row (glTF convention)
};

// Makes an RGBA texture from 8-bit file data; `srgb` decodes colour to linear.
Texture textureFromImage(std::string name, Buffer rgba, bool srgb);
// A procedural checkerboard (linear colours), `cells` squares per side.
Texture checkerTexture(int size, int cells, Vec3 a, Vec3 b);

}  // namespace tandem
