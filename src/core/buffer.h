// A named frame buffer: width x height pixels of `channels` floats, interleaved per pixel.
// Every G-buffer target, mask and image is one of these, so passes, AOV output and metrics
// treat them alike (ids are stored as exact small integers in float).
#pragma once
#include <cstddef>
#include <vector>

#include "core/math.h"

namespace tandem {

struct Buffer {
  int width = 0, height = 0, channels = 0;
  std::vector<float> data;

  Buffer() = default;
  Buffer(int w, int h, int c, float fill = 0.0f)
      : width(w), height(h), channels(c), data(size_t(w) * h * c, fill) {}

  size_t pixelCount() const { return size_t(width) * height; }
  float* at(int x, int y) { return &data[(size_t(y) * width + x) * channels]; }
  const float* at(int x, int y) const { return &data[(size_t(y) * width + x) * channels]; }
  Vec3 rgb(int x, int y) const {
    const float* p = at(x, y);
    return channels >= 3 ? Vec3(p[0], p[1], p[2]) : Vec3(p[0]);
  }
  void setRgb(int x, int y, Vec3 c) {
    float* p = at(x, y);
    p[0] = c.x;
    p[1] = c.y;
    p[2] = c.z;
  }
  void fill(float v) { std::fill(data.begin(), data.end(), v); }
  bool sameShape(const Buffer& o) const {
    return width == o.width && height == o.height && channels == o.channels;
  }
};

}  // namespace tandem
