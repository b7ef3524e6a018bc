// Raster shadow maps: the cheap stand-in for shadow rays on pixels the heuristic did not select
// (what production hybrids fall back to). One depth map per directional light (orthographic,
// over the scene's bounds), per spot light (its cone) and six per point light (a cube), drawn by
// the same rasterizer as the G-buffer. They are redrawn only when geometry or lights change, so
// a moving camera reuses them.
#pragma once
#include <vector>

#include "raster/rasterizer.h"
#include "scene/camera.h"
#include "scene/frame_scene.h"

namespace tandem {

class ShadowMaps {
 public:
  // Redraws the maps when the geometry, the lights or the resolution changed.
  void update(const FrameScene& fs, int resolution);
  // Fraction (0..1, 2x2 percentage-closer filtered) of light `i` reaching point p with unit
  // normal n; 1 for lights that cast no shadows or where p lies outside every map.
  float visibility(size_t i, Vec3 p, Vec3 n) const;
  int redraws() const { return redraws_; }

 private:
  struct Face {
    Camera camera;
    VisibilityBuffer map;
    float texelPerDistance = 0;  // a texel's world width per unit distance (ortho: the width)
  };
  std::vector<std::vector<Face>> faces_;  // per light
  uint64_t geometryVersion_ = ~0ull;
  std::vector<float> lightKey_;
  int resolution_ = 0, redraws_ = 0;
  Rasterizer raster_;
};

}  // namespace tandem
