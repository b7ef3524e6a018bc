// The G-buffer's targets, declared once (Walewski et al. 2019 Table 2, extended): each slot's
// channels, kind and channel names, for the passes that write it (raster/gbuffer.h) and every
// pass that reads a target (gbufferSlot), so writer and readers cannot disagree.
//
//   depth        1  reversed-Z depth (1 near plane, 0 background)
//   position     3  world position
//   normal       3  shading normal (normal map applied), world space
//   geo_normal   3  geometric normal
//   diffuse      4  diffuse albedo + diffuse opacity
//   specular     4  specular colour + exponent
//   emission     3  emitted radiance
//   ambient      3  ambient colour
//   optical      3  reflectivity, index of refraction, opacity
//   object_id    1  object index, -1 for background
//   material_id  1  material index, -1 for background
//   motion       2  screen-space motion in pixels: this frame's position minus last frame's
#pragma once
#include <string>
#include <vector>

#include "core/buffer.h"

namespace tandem {

struct DiffuseChannels {
  static constexpr int kRgb = 0, kOpacity = 3, kCount = 4;
};
struct SpecularChannels {
  static constexpr int kRgb = 0, kExponent = 3, kCount = 4;
};
struct OpticalChannels {
  static constexpr int kReflectivity = 0, kIor = 1, kOpacity = 2, kCount = 3;
};

// Every target, in GBufferView's order.
const std::vector<BufferSlot>& gbufferLayout();
// One target's declaration by slot name (a logic_error for a name that is none).
const BufferSlot& gbufferSlot(const std::string& slot);

}  // namespace tandem
