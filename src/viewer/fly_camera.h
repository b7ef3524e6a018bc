// The viewer's camera: position, yaw and pitch (degrees), moved with WASD/QE and turned with the
// mouse, converted to and from the scene's CameraDesc (look-at form) so views can be saved in
// the scene file format and rendered by `render`.
#pragma once
#include "scene/camera.h"

namespace tandem {

struct FlyCamera {
  Vec3 position{0, 1, 4};
  float yawDeg = 0, pitchDeg = 0;  // yaw about +Y from -Z towards +X; pitch up, in (-89, 89)
  float speed = 2.0f;              // metres per second
  float focusDistance = 5.0f;      // distance to the look-at point written back

  static FlyCamera fromDesc(const CameraDesc& d);
  // `base` supplies everything but position and look-at (fov, lens, planes).
  CameraDesc toDesc(const CameraDesc& base) const;
  Vec3 forward() const;
  Vec3 right() const;
  // Moves by (right, up, forward) axes in [-1, 1] for dt seconds; up is world +Y.
  void move(float right, float up, float forward, float dt);
  // Turns by a mouse delta in pixels (degrees per pixel given).
  void look(float dxPixels, float dyPixels, float degPerPixel = 0.15f);
};

}  // namespace tandem
