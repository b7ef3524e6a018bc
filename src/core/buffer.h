// A named frame buffer: width x height pixels of `channels` floats, interleaved per pixel.
// Every G-buffer target, mask, list and image is one of these, so passes, AOV output and metrics
// treat them alike (ids are stored as exact small integers in float). A buffer knows its kind, so
// the AOV writer and the viewer show it correctly without knowing its name.
#pragma once
#include <algorithm>
#include <any>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "core/math.h"

namespace tandem {

// What the values of a buffer mean (how to show them, what may feed what).
enum class BufferKind {
  Color,     // linear HDR radiance (tonemapped for display)
  Display,   // display-encoded sRGB in [0,1] (a pipeline's final image)
  Depth,     // reversed-Z depth: 1 at the near plane, 0 background
  Position,  // world position
  Normal,    // unit vectors
  Id,        // small integers, -1 none (false-coloured)
  Motion,    // screen-space motion in pixels (2 channels)
  Mask,      // weights or flags in [0,1], one channel per mask
  Count,     // non-negative integers (samples, rays)
  Signed,    // signed scalars (a circle of confusion: < 0 near field, > 0 far field)
  Variance,  // variance of a mean (shown as standard error)
  Material,  // material terms in [0,1] (albedo, specular, optical)
  List,      // records, not pixels: an N x 1 list (per object, per sample)
  Record,    // a typed value, not pixels: a struct one pass hands another (Buffer::record)
};
const char* kindName(BufferKind k);

// A buffer's size relative to the frame: the frame, 1/2 or 1/4 of it (rounded up), a fixed size
// (a 1 x 1 value, an N x 1 list), or sized by its pass at run time (a list whose length depends on
// the scene).
struct Extent {
  enum class Scale { Frame, Half, Quarter, Fixed, Any };
  Scale scale = Scale::Frame;
  int width = 0, height = 0;  // Fixed only

  static Extent frame() { return {}; }
  static Extent half() { return {Scale::Half, 0, 0}; }
  static Extent quarter() { return {Scale::Quarter, 0, 0}; }
  static Extent fixed(int w, int h) { return {Scale::Fixed, w, h}; }
  static Extent any() { return {Scale::Any, 0, 0}; }
  int divisor() const { return scale == Scale::Half ? 2 : scale == Scale::Quarter ? 4 : 1; }
  // Pixel size for a frame of fw x fh (Any: 0 x 0, the pass decides).
  void resolve(int fw, int fh, int& w, int& h) const {
    if (scale == Scale::Fixed) {
      w = width;
      h = height;
    } else if (scale == Scale::Any) {
      w = h = 0;
    } else {
      w = (fw + divisor() - 1) / divisor();
      h = (fh + divisor() - 1) / divisor();
    }
  }
  bool operator==(const Extent& o) const {
    return scale == o.scale && (scale != Scale::Fixed || (width == o.width && height == o.height));
  }
  std::string name() const;
};

// A pass's buffer slot: its name (fixed by the pass), channel count, kind, extent, and whether it
// reads last frame's value of the buffer (a history input: valid unless the history was reset) or
// may be missing (an optional input). A Record slot names the type it carries instead of
// channels and an extent. A multi-channel slot names its channels (what each float means: "r",
// "coc", "frames"), unless its kind names them (channelNamesOf); a pipeline checks that writer
// and reader agree, and `tandem pipeline` shows them.
struct BufferSlot {
  std::string slot;
  int channels = 1;
  BufferKind kind = BufferKind::Color;
  Extent extent = Extent::frame();
  bool history = false;
  bool optional = false;
  std::string recordType{};                 // Record: the struct's name (checked like channels)
  std::vector<std::string> channelNames{};  // one per channel; empty: by kind

  // This slot with `names` as its channels (and as many channels).
  BufferSlot named(std::vector<std::string> names) const {
    BufferSlot s = *this;
    s.channels = int(names.size());
    s.channelNames = std::move(names);
    return s;
  }
};

// A slot's channel names: its own, else its kind's for the shapes that name themselves (3-channel
// colour "r", "g", "b"; positions and normals "x", "y", "z"; motion "dx", "dy"). Empty for a
// single channel (the slot's name says what it is) and for a multi-channel slot of another shape
// that names none (a declaration bug the suite catches).
std::vector<std::string> channelNamesOf(const BufferSlot& s);
// "r, g, b" (for messages and docs).
std::string channelList(const std::vector<std::string>& names);

// A slot carrying a typed value of the struct named `type` (FrameContext::outputRecord).
inline BufferSlot recordSlot(std::string slot, std::string type) {
  return {.slot = std::move(slot),
          .channels = 0,
          .kind = BufferKind::Record,
          .extent = Extent::any(),
          .recordType = std::move(type)};
}

struct Buffer {
  int width = 0, height = 0, channels = 0;
  BufferKind kind = BufferKind::Color;
  std::vector<float> data;
  std::any record;  // Record: the value (no pixels)

  Buffer() = default;
  Buffer(int w, int h, int c, float fill = 0.0f, BufferKind k = BufferKind::Color)
      : width(w), height(h), channels(c), kind(k), data(size_t(w) * h * c, fill) {}

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
