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
  // Motion blur: world positions and normals at FrameScene::motionSteps evenly spaced times over
  // the shutter [time, shutterClose] (step 0 = positions); empty when the object stands still
  // while the shutter is open. Between steps vertices move linearly, as Embree interpolates them.
  std::vector<std::vector<Vec3>> stepPositions, stepNormals;
  Bounds3 bounds;  // of positions and every motion step: per-object culling
};

struct FrameScene {
  const Scene* scene = nullptr;
  float time = 0, prevTime = 0;
  std::vector<FrameObject> objects;
  float shutterClose = 0;   // == time: no motion blur
  float shutterLength = 0;  // seconds, as the last update was given it
  int motionSteps = 4;      // time steps per moving object while the shutter is open
  // Change whenever world-space geometry changed (any object / an object that is not animated),
  // to a value no FrameScene of this process had before.
  uint64_t geometryVersion = 0;
  uint64_t staticVersion = 0;

  // Re-evaluates transforms; recomputes world geometry only for objects whose matrix changed.
  // A shutter > 0 (seconds) keeps the shutter's time steps of objects that move in it.
  void update(const Scene& s, float t, float tPrev, float shutter = 0.0f);
  bool motionBlur() const { return shutterClose > time; }
};

// Vertex v of object o at shutter fraction tau in [0,1] (linear between time steps).
Vec3 positionAt(const FrameObject& o, size_t v, float tau);
Vec3 normalAt(const FrameObject& o, size_t v, float tau);

}  // namespace tandem
