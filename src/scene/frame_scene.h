// The scene evaluated at one frame time: world-space geometry per object, shared by the
// rasterizer and the ray tracer ("one scene, two views"), plus the previous frame's object
// matrices for motion vectors.
#pragma once
#include <vector>

#include "scene/scene.h"

namespace tandem {

struct FrameObject {
  Mat4 world, prevWorld, normalMatrix;
  Mat4 worldToPrev;    // carries this frame's world points to last frame's (motion vectors)
  bool moved = false;  // worldToPrev is not the identity
  std::vector<Vec3> positions;  // world space
  std::vector<Vec3> normals;    // world space, unit
  std::vector<Vec4> tangents;   // world space xyz, w = bitangent sign
};

struct FrameScene {
  const Scene* scene = nullptr;
  float time = 0, prevTime = 0;
  std::vector<FrameObject> objects;
  uint64_t geometryVersion = 0;  // bumps whenever world-space geometry changed

  // Re-evaluates transforms; recomputes world geometry only for objects whose matrix changed.
  void update(const Scene& s, float t, float tPrev);
};

}  // namespace tandem
