#include "pipeline/aov.h"

#include <cmath>

#include "core/color.h"
#include "core/file_commit.h"
#include "core/image_io.h"

namespace tandem {

Vec3 idColor(int id) {
  if (id < 0) return {0, 0, 0};
  // Integer hash (Wang) -> hue-ish colour with enough brightness to read.
  uint32_t h = uint32_t(id) * 0x9E3779B9u;
  h ^= h >> 15;
  h *= 0x2C1B3C6Du;
  h ^= h >> 12;
  return {0.25f + 0.75f * ((h & 0xff) / 255.0f), 0.25f + 0.75f * (((h >> 8) & 0xff) / 255.0f),
          0.25f + 0.75f * (((h >> 16) & 0xff) / 255.0f)};
}

Buffer visualizeBuffer(const Buffer& b, float scale) {
  Buffer out(b.width, b.height, 3);
  const size_t n = b.pixelCount();
  auto set = [&](size_t i, Vec3 c) { out.setRgb(int(i % b.width), int(i / b.width), c); };
  if (b.kind == BufferKind::Display) {
    for (size_t i = 0; i < n; ++i) set(i, b.rgb(int(i % b.width), int(i / b.width)));
    return out;
  }
  if (b.kind == BufferKind::Id) {
    for (size_t i = 0; i < n; ++i) set(i, idColor(int(std::lround(b.data[i * b.channels]))));
    return out;
  }
  if (b.kind == BufferKind::Depth) {
    // Reversed-Z: brighter is nearer; stretch the visible range to [0,1].
    float lo = 1e30f, hi = 0;
    for (size_t i = 0; i < n; ++i)
      if (b.data[i * b.channels] > 0) {
        lo = std::min(lo, b.data[i * b.channels]);
        hi = std::max(hi, b.data[i * b.channels]);
      }
    for (size_t i = 0; i < n; ++i) {
      float d = b.data[i * b.channels];
      float v = d > 0 && hi > lo ? 0.1f + 0.9f * (d - lo) / (hi - lo) : (d > 0 ? 1.0f : 0.0f);
      set(i, Vec3(v));
    }
    return out;
  }
  if (b.kind == BufferKind::Normal && b.channels >= 3) {
    for (size_t i = 0; i < n; ++i) {
      const float* p = &b.data[i * b.channels];
      Vec3 v{p[0], p[1], p[2]};
      set(i, length(v) > 0 ? v * 0.5f + Vec3(0.5f) : Vec3(0.0f));
    }
    return out;
  }
  if (b.kind == BufferKind::Motion && b.channels >= 2) {
    float m = 1e-6f;
    for (size_t i = 0; i < n; ++i)
      m = std::max({m, std::abs(b.data[i * b.channels]), std::abs(b.data[i * b.channels + 1])});
    for (size_t i = 0; i < n; ++i)
      set(i, {0.5f + 0.5f * b.data[i * b.channels] / m,
              0.5f + 0.5f * b.data[i * b.channels + 1] / m, 0.5f});
    return out;
  }
  if (b.kind == BufferKind::Position) {
    Bounds3 bb;
    for (size_t i = 0; i < n; ++i) bb.extend(b.rgb(int(i % b.width), int(i / b.width)));
    Vec3 ext = vmax(bb.extent(), Vec3(1e-6f));
    for (size_t i = 0; i < n; ++i) {
      Vec3 p = b.rgb(int(i % b.width), int(i / b.width)) - bb.lo;
      set(i, {p.x / ext.x, p.y / ext.y, p.z / ext.z});
    }
    return out;
  }
  if (b.kind == BufferKind::Variance) {
    // Standard error of each pixel mean, times `scale`, as grey: the noise left to converge.
    for (size_t i = 0; i < n; ++i)
      set(i, Vec3(std::min(std::sqrt(std::max(b.data[i * b.channels], 0.0f)) * scale, 1.0f)));
    return out;
  }
  if (b.kind == BufferKind::Count || b.kind == BufferKind::Signed) {
    // Scaled by the largest magnitude of the first channel; signed: blue below 0, red above.
    float m = 1e-6f;
    for (size_t i = 0; i < n; ++i) m = std::max(m, std::abs(b.data[i * b.channels]));
    for (size_t i = 0; i < n; ++i) {
      const float v = b.data[i * b.channels] / m;
      set(i, b.kind == BufferKind::Count ? Vec3(v)
                                         : Vec3(std::max(v, 0.0f), 0.0f, std::max(-v, 0.0f)));
    }
    return out;
  }
  if (b.kind == BufferKind::Color) {
    for (size_t i = 0; i < n; ++i)
      set(i, tonemapPixel(b.rgb(int(i % b.width), int(i / b.width)), 0.0f, ToneOperator::Aces));
    return out;
  }
  // Material terms, optical properties, masks, counts, lists: shown as stored (clamped), one
  // channel as grey.
  for (size_t i = 0; i < n; ++i) {
    const float* p = &b.data[i * b.channels];
    Vec3 c = b.channels >= 3 ? Vec3(p[0], p[1], p[2]) : Vec3(p[0]);
    set(i, vmin(vmax(c, Vec3(0.0f)), Vec3(1.0f)));
  }
  return out;
}

std::vector<unsigned char> encodeBuffer(const std::string& path, const Buffer& b,
                                        const std::vector<std::string>& channels) {
  return hasExtension(path, ".exr") ? encodeExrLayers(path, {{"", &b, channels}})
                                    : encodePng(path, visualizeBuffer(b));
}

void writeBuffer(const std::string& path, const Buffer& b) {
  writeFileAtomically(path, encodeBuffer(path, b));
}

}  // namespace tandem
