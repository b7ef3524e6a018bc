// Albedo demodulation of a path-traced estimate (Dammertz et al. 2010's diffuse-buffer step):
// illumination = (colour - emission) / albedo, and back. Filters and temporal accumulation work
// on the illumination, so texture detail comes from this frame's G-buffer and is never blurred
// or lagged. Sky pixels (depth 0) and near-black albedo (< 0.01) are left as colour.
#pragma once
#include <algorithm>

#include "core/buffer.h"
#include "shading/gbuffer_layout.h"

namespace tandem {

struct Demodulation {
  const Buffer& diffuse;
  const Buffer& emission;
  const Buffer& depth;
  bool enabled = true;

  float albedo(int x, int y, int k) const {
    const float a = diffuse.at(x, y)[DiffuseChannels::kRgb + k];
    return enabled && depth.at(x, y)[0] > 0 && a > 0.01f ? std::min(a, 1.0f) : 1.0f;
  }
  float emitted(int x, int y, int k) const {
    return enabled && depth.at(x, y)[0] > 0 ? emission.at(x, y)[k] : 0.0f;
  }
  float illumination(float colour, int x, int y, int k) const {
    return (colour - emitted(x, y, k)) / albedo(x, y, k);
  }
  float colour(float illumination, int x, int y, int k) const {
    return illumination * albedo(x, y, k) + emitted(x, y, k);
  }
};

}  // namespace tandem
