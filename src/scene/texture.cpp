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
      if ((n & (n - 1)) == 0) return i & (n - 1);  // powers of two: no division (same result)
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

namespace {

// sRGB-encoded byte -> linear value, and the identity for linear textures.
struct DecodeTables {
  float srgb[256], linear[256];
  DecodeTables() {
    for (int n = 0; n < 256; ++n) {
      srgb[n] = srgbToLinear(float(n) / 255.0f);
      linear[n] = float(n) / 255.0f;
    }
  }
};
const DecodeTables& decodeTables() {
  static const DecodeTables t;
  return t;
}

uint8_t encodeByte(float v, bool srgb) {
  if (srgb) v = linearToSrgb(v);
  return uint8_t(std::clamp(int(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)), 0, 255));
}

// Channel by channel in registers: building the four texels as vectors on the stack and reading
// them back stalled on store forwarding.
Vec4 bilinear(const Texture::Level& l, Vec2 uv, WrapMode ws, WrapMode wt, const float* table,
              const float* alphaTable) {
  const int w = l.width, h = l.height;
  // Keep the coordinate in a modest range before converting to int (huge UVs stay exact enough).
  float fx = std::clamp(uv.x * float(w) - 0.5f, -1e7f, 1e7f);
  float fy = std::clamp(uv.y * float(h) - 0.5f, -1e7f, 1e7f);
  const float x0f = std::floor(fx), y0f = std::floor(fy);
  const float tx = fx - x0f, ty = fy - y0f;
  const int x0 = int(x0f), y0 = int(y0f);
  const int xa = wrapIndex(x0, w, ws), xb = wrapNext(xa, x0 + 1, w, ws);
  const int ya = wrapIndex(y0, h, wt), yb = wrapNext(ya, y0 + 1, h, wt);
  const uint8_t* rowA = &l.rgba[size_t(ya) * size_t(w) * 4];
  const uint8_t* rowB = &l.rgba[size_t(yb) * size_t(w) * 4];
  const uint8_t *p00 = rowA + size_t(xa) * 4, *p10 = rowA + size_t(xb) * 4;
  const uint8_t *p01 = rowB + size_t(xa) * 4, *p11 = rowB + size_t(xb) * 4;
  float out[4];
  for (int k = 0; k < 4; ++k) {
    const float* t = k < 3 ? table : alphaTable;
    const float top = t[p00[k]] * (1 - tx) + t[p10[k]] * tx;
    const float bottom = t[p01[k]] * (1 - tx) + t[p11[k]] * tx;
    out[k] = top * (1 - ty) + bottom * ty;
  }
  return {out[0], out[1], out[2], out[3]};
}

}  // namespace

Vec4 Texture::sample(Vec2 uv, float lod) const {
  if (levels.empty()) return {1, 1, 1, 1};
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = {0, 0};
  const DecodeTables& tables = decodeTables();
  const float *table = srgb ? tables.srgb : tables.linear, *alpha = tables.linear;
  const float top = float(levels.size() - 1);
  if (!(lod > 0.0f)) return bilinear(levels[0], uv, wrapS, wrapT, table, alpha);
  lod = std::min(lod, top);
  const int l0 = int(lod);
  const float t = lod - float(l0);
  const Vec4 a = bilinear(levels[size_t(l0)], uv, wrapS, wrapT, table, alpha);
  if (t <= 0.0f || l0 + 1 > int(top)) return a;
  return a * (1 - t) + bilinear(levels[size_t(l0) + 1], uv, wrapS, wrapT, table, alpha) * t;
}

float Texture::lodFor(float uvPerPixel) const {
  if (levels.empty() || !(uvPerPixel > 0.0f)) return 0.0f;
  const float texels = uvPerPixel * float(std::max(levels[0].width, levels[0].height));
  return texels > 1.0f ? std::log2(texels) : 0.0f;
}

void Texture::buildLevels() {
  levels.clear();
  int w = texels.width, h = texels.height;
  if (w <= 0 || h <= 0) return;
  // Level 0 from the float texels; each further level a 2x2 box of the one above in linear
  // space (odd sizes: the last row/column folds into its neighbour).
  std::vector<float> linear(texels.data.begin(), texels.data.end());
  if (texels.channels != 4) {
    linear.assign(size_t(w) * size_t(h) * 4, 1.0f);
    for (size_t i = 0; i < size_t(w) * size_t(h); ++i)
      for (int k = 0; k < std::min(texels.channels, 4); ++k)
        linear[i * 4 + size_t(k)] = texels.data[i * size_t(texels.channels) + size_t(k)];
  }
  while (true) {
    Level l{w, h, std::vector<uint8_t>(size_t(w) * size_t(h) * 4)};
    for (size_t i = 0; i < linear.size(); ++i)
      l.rgba[i] = encodeByte(linear[i], srgb && i % 4 != 3);
    levels.push_back(std::move(l));
    if (w == 1 && h == 1) break;
    const int nw = std::max(w / 2, 1), nh = std::max(h / 2, 1);
    std::vector<float> next(size_t(nw) * size_t(nh) * 4, 0.0f);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const int nx = std::min(x / 2, nw - 1), ny = std::min(y / 2, nh - 1);
        for (int k = 0; k < 4; ++k)
          next[(size_t(ny) * size_t(nw) + size_t(nx)) * 4 + size_t(k)] +=
              linear[(size_t(y) * size_t(w) + size_t(x)) * 4 + size_t(k)];
      }
    // Each coarse texel averaged over the fine texels that folded into it.
    for (int ny = 0; ny < nh; ++ny)
      for (int nx = 0; nx < nw; ++nx) {
        const int cx = (nx == nw - 1 ? w - 2 * nx : 2), cy = (ny == nh - 1 ? h - 2 * ny : 2);
        const float inv = 1.0f / float(std::max(cx, 1) * std::max(cy, 1));
        for (int k = 0; k < 4; ++k)
          next[(size_t(ny) * size_t(nw) + size_t(nx)) * 4 + size_t(k)] *= inv;
      }
    linear.swap(next);
    w = nw;
    h = nh;
  }
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
  t.srgb = srgb;
  t.buildLevels();
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
  t.buildLevels();
  return t;
}

}  // namespace tandem
