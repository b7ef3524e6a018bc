// The shadow-map lookup of ShadowMaps::visibility for up to 16 points of one map face at once
// (a Highway kernel): offset along the normal, projection, one depth threshold, 2x2
// percentage-closer taps gathered from the map.
#pragma once
#include <cstddef>

#include "core/math.h"

namespace tandem {

struct ShadowFace {
  const float* depth;  // width x height reversed-Z depth
  int width, height;
  float row[3][4];  // the camera's viewProj rows x, y and w
  Vec3 eye, forward;
  float texelPerDistance;  // perspective: a texel's width per unit distance; ortho: the width
  bool perspective;
  float nearPlane, farPlane;
};

// For lanes k < n with use[k] != 0: out[k] = the lit fraction of point (px, py, pz)[k] with
// normal (nx, ny, nz)[k] in this face, or 1 where the point lies outside the face. Other lanes
// are left as they are.
void shadowLookupBatch(const ShadowFace& f, const float* px, const float* py, const float* pz,
                       const float* nx, const float* ny, const float* nz, const float* use,
                       size_t n, float* out);

}  // namespace tandem
