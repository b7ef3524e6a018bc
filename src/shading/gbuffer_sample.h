// Reads a SurfaceSample back from the G-buffer, the inverse of GBufferView::write, so image-space
// passes shade exactly what a ray hit would have shaded.
#pragma once
#include <functional>
#include <vector>

#include "core/buffer.h"
#include "core/math.h"
#include "shading/surface.h"

namespace tandem {

const std::vector<BufferSlot>& gbufferSampleSlots();

struct ShadeBatch;

class GBufferReader {
 public:
  // `source(slot)` gives the buffer of one of gbufferSampleSlots().
  explicit GBufferReader(const std::function<const Buffer&(const BufferSlot&)>& source);
  // False for background pixels.
  bool read(int x, int y, SurfaceSample& s) const;
  // The position alone; false for background.
  bool position(int x, int y, Vec3& p) const {
    const size_t i = size_t(y) * size_t(width_) + size_t(x);
    if (g_.objectId[i] < 0) return false;
    p = {g_.position[3 * i], g_.position[3 * i + 1], g_.position[3 * i + 2]};
    return true;
  }
  // The same pixel straight into lane `lane` of a shading batch (what shading reads; the eye
  // direction is the caller's); false for background.
  bool read(int x, int y, ShadeBatch& b, int lane) const;
  // Lanes [0, n) of a batch from the n pixels (x .. x + n - 1, y) of one row, with their eye
  // directions: normalize(eye - position) when `perspective`, else `eye` itself (-forward).
  // n is a multiple of ShadeBatch::kMax. False, the lanes undefined, when any pixel is
  // background. The same lanes as read() pixel by pixel, bit for bit (gbuffer_span.cpp), and
  // the box around their positions.
  bool readSpan(int x, int y, int n, ShadeBatch& b, bool perspective, Vec3 eye,
                Bounds3& bounds) const;

  struct Planes {
    const float *position, *normal, *geoNormal, *diffuse, *specular, *emission, *ambient, *optical,
        *objectId, *materialId;
  };

 private:
  Planes g_;
  int width_;
};

}  // namespace tandem
