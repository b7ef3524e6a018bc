// Raster shadow maps: the cheap stand-in for shadow rays on pixels the heuristic did not select
// (what production hybrids fall back to). One depth map per directional light (orthographic,
// over the scene's bounds), per spot light (its cone) and six per point light (a cube), drawn by
// the same rasterizer as the G-buffer. Casters that are not animated are drawn once (again only
// when lights or static geometry change); animated casters are drawn over a copy of that depth
// whenever they moved. A moving camera reuses the maps as they are.
#pragma once
#include <vector>

#include "passes/shadow_lookup.h"
#include "raster/rasterizer.h"
#include "scene/camera.h"
#include "scene/frame_scene.h"

namespace tandem {

class ShadowMaps {
 public:
  // Redraws what changed: everything for new lights, resolution or static geometry; the
  // animated casters over the static depth when only they moved.
  void update(const FrameScene& fs, int resolution);
  // Fraction (0..1, 2x2 percentage-closer filtered) of light `i` reaching point p with unit
  // normal n; 1 for lights that cast no shadows or where p lies outside every map.
  float visibility(size_t i, Vec3 p, Vec3 n) const;
  // The same for up to 16 points (structure of arrays, 16 entries each) in one SIMD kernel:
  // out[k] = visibility(i, p[k], n[k]) for the lanes k < count with use[k] != 0 (equal up to
  // rounding at a tap's depth threshold).
  void visibilityBatch(size_t i, const float* px, const float* py, const float* pz, const float* nx,
                       const float* ny, const float* nz, const float* use, int count,
                       float* out) const;
  int redraws() const { return redraws_; }              // full (static) redraws
  int movingRedraws() const { return movingRedraws_; }  // animated casters drawn again

 private:
  struct Face {
    Camera camera;
    VisibilityBuffer map;            // only depth is read (object / prim are scratch)
    std::vector<float> staticDepth;  // the static casters' depth, when animated ones exist
    ShadowFace lookup{};             // what the batch kernel reads (depth: map's, at lookup)
    float texelPerDistance = 0;      // a texel's world width per unit distance (ortho: the width)
  };
  void drawStatic(const FrameScene& fs, const std::vector<uint8_t>& still, bool keepCopy);

  std::vector<std::vector<Face>> faces_;  // per light
  uint64_t geometryVersion_ = ~0ull, staticVersion_ = ~0ull;
  const Scene* scene_ = nullptr;
  std::vector<float> lightKey_;
  int resolution_ = 0, redraws_ = 0, movingRedraws_ = 0;
  Rasterizer raster_;
};

}  // namespace tandem
