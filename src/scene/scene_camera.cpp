#include "scene/scene_camera.h"

#include <cmath>

namespace tandem {

CameraDesc defaultCamera(const Scene& s) {
  CameraDesc c = s.camera;
  if (!s.hasCamera) {
    Bounds3 b = s.bounds();
    Vec3 centre = b.center();
    float radius = std::max(length(b.extent()) * 0.5f, 1e-3f);
    c.lookAt = centre;
    c.position = centre + Vec3(0, radius * 0.3f, radius * 2.2f);
    c.nearPlane = std::max(radius * 1e-3f, 1e-5f);
  }
  fitNearPlane(c);
  return c;
}

void fitNearPlane(CameraDesc& c) {
  c.nearPlane = std::min(c.nearPlane, length(c.lookAt - c.position) * 0.05f);
}

CameraDesc pathCameraAt(const Scene& s, const CameraDesc& base, float t) {
  return s.cameraPath.empty() ? base : sampleCameraPath(s.cameraPath, base, t);
}

CameraDesc pathCamera(const Scene& s, const CameraDesc& base, int i, int n) {
  float u = n > 1 ? float(i) / float(n - 1) : 0.0f;
  if (!s.cameraPath.empty()) {
    float t0 = s.cameraPath.front().time, t1 = s.cameraPath.back().time;
    return sampleCameraPath(s.cameraPath, base, t0 + (t1 - t0) * u);
  }
  CameraDesc c = base;
  Vec3 off = base.position - base.lookAt;
  float a = radians(-20.0f + 40.0f * u);
  c.position = base.lookAt + Vec3(off.x * std::cos(a) + off.z * std::sin(a), off.y,
                                  -off.x * std::sin(a) + off.z * std::cos(a));
  return c;
}

}  // namespace tandem
