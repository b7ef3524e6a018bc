// Reads a SurfaceSample back from the G-buffer, the inverse of GBufferView::write, so image-space
// passes shade exactly what a ray hit would have shaded.
#pragma once
#include <functional>
#include <vector>

#include "core/buffer.h"
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
  // The same pixel straight into lane `lane` of a shading batch (what shading reads; the eye
  // direction is the caller's); false for background.
  bool read(int x, int y, ShadeBatch& b, int lane) const;

 private:
  const float *position_, *normal_, *geoNormal_, *diffuse_, *specular_, *emission_, *ambient_,
      *optical_, *objectId_, *materialId_;
  int width_;
};

}  // namespace tandem
