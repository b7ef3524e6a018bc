#include "scene/animation.h"

namespace tandem {

namespace {

// Finds the segment around t and the blend factor within it.
template <class Key>
void locate(const std::vector<Key>& keys, float t, size_t& i, float& u) {
  i = 0;
  u = 0;
  if (keys.size() < 2 || t <= keys.front().time) return;
  if (t >= keys.back().time) {
    i = keys.size() - 1;
    return;
  }
  while (i + 1 < keys.size() && keys[i + 1].time < t) ++i;
  float span = keys[i + 1].time - keys[i].time;
  u = span > 0 ? (t - keys[i].time) / span : 0.0f;
}

}  // namespace

Transform sampleTransform(const std::vector<TransformKey>& keys, float t) {
  size_t i;
  float u;
  locate(keys, t, i, u);
  if (u == 0.0f) return keys[i].transform;
  const Transform &a = keys[i].transform, &b = keys[i + 1].transform;
  return {lerp(a.position, b.position, u), lerp(a.rotationDeg, b.rotationDeg, u),
          lerp(a.scale, b.scale, u)};
}

CameraDesc sampleCameraPath(const std::vector<CameraKey>& keys, const CameraDesc& base, float t) {
  CameraDesc d = base;
  if (keys.empty()) return d;
  size_t i;
  float u;
  locate(keys, t, i, u);
  d.position = keys[i].position;
  d.lookAt = keys[i].lookAt;
  if (u > 0.0f) {
    d.position = lerp(keys[i].position, keys[i + 1].position, u);
    d.lookAt = lerp(keys[i].lookAt, keys[i + 1].lookAt, u);
  }
  return d;
}

Vec2 sampleGazeTrace(const std::vector<GazeKey>& keys, float t) {
  size_t i;
  float u;
  locate(keys, t, i, u);
  if (u <= 0.0f) return keys[i].gaze;
  const Vec2 a = keys[i].gaze, b = keys[i + 1].gaze;
  return Vec2(a.x + (b.x - a.x) * u, a.y + (b.y - a.y) * u);
}

}  // namespace tandem
