#include "viewer/fly_camera.h"

#include <algorithm>
#include <cmath>

namespace tandem {

FlyCamera FlyCamera::fromDesc(const CameraDesc& d) {
  FlyCamera c;
  c.position = d.position;
  Vec3 f = d.lookAt - d.position;
  c.focusDistance = std::max(length(f), 1e-3f);
  f = f / c.focusDistance;
  c.yawDeg = std::atan2(f.x, -f.z) * 180.0f / kPi;
  c.pitchDeg = std::clamp(std::asin(std::clamp(f.y, -1.0f, 1.0f)) * 180.0f / kPi, -89.0f, 89.0f);
  return c;
}

Vec3 FlyCamera::forward() const {
  const float y = radians(yawDeg), p = radians(pitchDeg);
  return {std::sin(y) * std::cos(p), std::sin(p), -std::cos(y) * std::cos(p)};
}

Vec3 FlyCamera::right() const {
  const float y = radians(yawDeg);
  return {std::cos(y), 0.0f, std::sin(y)};
}

CameraDesc FlyCamera::toDesc(const CameraDesc& base) const {
  CameraDesc d = base;
  d.position = position;
  d.lookAt = position + forward() * focusDistance;
  d.up = {0, 1, 0};
  return d;
}

void FlyCamera::move(float r, float u, float f, float dt) {
  position += (right() * r + Vec3(0, 1, 0) * u + forward() * f) * (speed * dt);
}

void FlyCamera::look(float dx, float dy, float degPerPixel) {
  yawDeg = std::fmod(yawDeg + dx * degPerPixel, 360.0f);
  pitchDeg = std::clamp(pitchDeg - dy * degPerPixel, -89.0f, 89.0f);
}

}  // namespace tandem
