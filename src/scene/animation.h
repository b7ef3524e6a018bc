// Keyframed transforms (per object) and camera paths, linearly interpolated in time and clamped
// at the ends. Times are in seconds.
#pragma once
#include <vector>

#include "core/math.h"
#include "scene/camera.h"

namespace tandem {

struct Transform {
  Vec3 position{0, 0, 0};
  Vec3 rotationDeg{0, 0, 0};  // Euler X, Y, Z in degrees (Walewski et al. 2019)
  Vec3 scale{1, 1, 1};
  Mat4 matrix() const {
    return Mat4::translate(position) * Mat4::eulerXYZ(rotationDeg) * Mat4::scale(scale);
  }
};

struct TransformKey {
  float time = 0;
  Transform transform;
};

struct CameraKey {
  float time = 0;
  Vec3 position, lookAt;
};

// A gaze point (fraction of the eye's viewport, 0,0 top left) at a time: Peres 2022's fovea
// follows it (scene file "gazeTrace").
struct GazeKey {
  float time = 0;
  Vec2 gaze{0.5f, 0.5f};
};

// Interpolated transform at time t; keys must be sorted by time and non-empty.
Transform sampleTransform(const std::vector<TransformKey>& keys, float t);
// Camera at time t along a path (position and look-at interpolated); other fields from base.
CameraDesc sampleCameraPath(const std::vector<CameraKey>& keys, const CameraDesc& base, float t);
// Gaze at time t along a trace (linear between keys, held beyond the ends); keys non-empty.
Vec2 sampleGazeTrace(const std::vector<GazeKey>& keys, float t);

}  // namespace tandem
