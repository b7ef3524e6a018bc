#include "scene/texture.h"

#include <cmath>

#include "core/color.h"

namespace tandem {

namespace {

int wrapIndex(int i, int n, WrapMode mode) {
  switch (mode) {
    case WrapMode::ClampToEdge:
      return std::clamp(i, 0, n - 1);
    case WrapMode::MirroredRepeat: {
      int period = 2 * n;
      int m = ((i % period) + period) % period;
      return m < n ? m : period - 1 - m;
    }
    case WrapMode::Repeat:
    default: {
      int m = i % n;
      return m < 0 ? m + n : m;
    }
  }
}

// The neighbour of wrapped index `a` (= wrap(i - 1)): repeat needs no second division, which
// halves the integer divisions of a bilinear fetch.
int wrapNext(int a, int i, int n, WrapMode mode) {
  if (mode == WrapMode::Repeat) return a + 1 == n ? 0 : a + 1;
  return wrapIndex(i, n, mode);
}

}  // namespace

Vec4 Texture::sample(Vec2 uv) const {
  const int w = texels.width, h = texels.height;
  if (w == 0 || h == 0) return {1, 1, 1, 1};
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = {0, 0};
  // Keep the coordinate in a modest range before converting to int (huge UVs stay exact enough).
  float fx = uv.x * w - 0.5f, fy = uv.y * h - 0.5f;
  fx = std::clamp(fx, -1e7f, 1e7f);
  fy = std::clamp(fy, -1e7f, 1e7f);
  float x0f = std::floor(fx), y0f = std::floor(fy);
  float tx = fx - x0f, ty = fy - y0f;
  int x0 = int(x0f), y0 = int(y0f);
  int xa = wrapIndex(x0, w, wrapS), xb = wrapNext(xa, x0 + 1, w, wrapS);
  int ya = wrapIndex(y0, h, wrapT), yb = wrapNext(ya, y0 + 1, h, wrapT);
  auto px = [&](int x, int y) {
    const float* p = texels.at(x, y);
    return Vec4(p[0], p[1], p[2], p[3]);
  };
  Vec4 top = px(xa, ya) * (1 - tx) + px(xb, ya) * tx;
  Vec4 bottom = px(xa, yb) * (1 - tx) + px(xb, yb) * tx;
  return top * (1 - ty) + bottom * ty;
}

Texture textureFromImage(std::string name, Buffer rgba, bool srgb) {
  Texture t;
  t.name = std::move(name);
  if (srgb) {
    // Texels come from 8-bit files (value = n / 255): decode through a 256-entry table.
    float table[256];
    for (int n = 0; n < 256; ++n) table[n] = srgbToLinear(n / 255.0f);
    for (size_t i = 0; i < rgba.pixelCount(); ++i)
      for (int k = 0; k < 3; ++k) {
        float& v = rgba.data[i * 4 + k];
        v = table[std::clamp(int(std::lround(v * 255.0f)), 0, 255)];
      }
  }
  t.texels = std::move(rgba);
  return t;
}

Texture checkerTexture(int size, int cells, Vec3 a, Vec3 b) {
  Texture t;
  t.name = "checker";
  t.texels = Buffer(size, size, 4, 1.0f);
  int cell = std::max(1, size / cells);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      Vec3 c = ((x / cell + y / cell) % 2) ? a : b;
      t.texels.setRgb(x, y, c);
    }
  return t;
}

}  // namespace tandem
