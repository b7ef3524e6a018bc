// Reads a SurfaceSample back from the G-buffer, the inverse of GBufferView::write, so image-space
// passes shade exactly what a ray hit would have shaded.
#pragma once
#include <vector>

#include "pipeline/pass.h"
#include "shading/surface.h"

namespace tandem {

struct FrameContext;

const std::vector<BufferSlot>& gbufferSampleSlots();

class GBufferReader {
 public:
  GBufferReader(const FrameContext& ctx, const Pass& pass);
  // False for background pixels.
  bool read(int x, int y, SurfaceSample& s) const;

 private:
  const float *position_, *normal_, *geoNormal_, *diffuse_, *specular_, *emission_, *ambient_,
      *optical_, *objectId_, *materialId_;
  int width_;
};

}  // namespace tandem
