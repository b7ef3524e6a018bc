#include "scene/frame_scene.h"

#include <algorithm>
#include <atomic>
#include <cstring>

#include "core/parallel.h"

namespace tandem {

namespace {

void transformMesh(const Mesh& m, const Mat4& w, std::vector<Vec3>& positions,
                   std::vector<Vec3>& normals) {
  const Mat4 nm = w.normalMatrix();
  positions.resize(m.positions.size());
  normals.resize(m.normals.size());
  parallelRange(m.positions.size(), [&](size_t b, size_t e) {
    for (size_t v = b; v < e; ++v) {
      positions[v] = w.transformPoint(m.positions[v]);
      if (v < m.normals.size()) normals[v] = normalize(nm.transformVector(m.normals[v]));
    }
  });
}

// Linear interpolation between the two time steps around shutter fraction tau.
Vec3 lerpSteps(const std::vector<std::vector<Vec3>>& steps, size_t v, float tau) {
  const float x = std::clamp(tau, 0.0f, 1.0f) * float(steps.size() - 1);
  const size_t i = std::min(size_t(x), steps.size() - 2);
  return lerp(steps[i][v], steps[i + 1][v], x - float(i));
}

}  // namespace

// Versions unique in the process, not per FrameScene: a FrameScene made afresh (a scene reset with
// new lights) must not repeat a version that caches keyed on it (the ray tracer's BVH, shadow
// maps, probes) saw for other geometry.
static uint64_t newVersion() {
  static std::atomic<uint64_t> versions{0};
  return ++versions;
}

Vec3 positionAt(const FrameObject& o, size_t v, float tau) {
  return o.stepPositions.size() < 2 ? o.positions[v] : lerpSteps(o.stepPositions, v, tau);
}

Vec3 normalAt(const FrameObject& o, size_t v, float tau) {
  return o.stepNormals.size() < 2 ? o.normals[v] : normalize(lerpSteps(o.stepNormals, v, tau));
}

void FrameScene::update(const Scene& s, float t, float tPrev, float shutter) {
  const float close = t + std::max(shutter, 0.0f);
  // The shutter's length as given, not close - t: that difference rounds differently at every
  // frame time, and a "new" shutter recomputes (and redraws, and rebuilds) everything.
  bool first =
      scene != &s || objects.size() != s.objects.size() || std::max(shutter, 0.0f) != shutterLength;
  shutterLength = std::max(shutter, 0.0f);
  shutterClose = close;
  scene = &s;
  time = t;
  prevTime = tPrev;
  if (first) objects.assign(s.objects.size(), FrameObject{});
  bool changed = first, staticChanged = first;
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const Object& o = s.objects[i];
    FrameObject& f = objects[i];
    Mat4 w = o.worldMatrix(t);
    f.prevWorld = o.worldMatrix(tPrev);
    f.worldToPrev = f.prevWorld * w.inverse();
    f.moved = !sameMatrix(f.prevWorld, w);
    const bool blurred = close > t && !sameMatrix(o.worldMatrix(close), w);
    if (!first && sameMatrix(w, f.world) && !blurred && f.stepPositions.empty()) continue;
    changed = true;
    staticChanged |= !o.animated();
    f.world = w;
    f.normalMatrix = w.normalMatrix();
    const Mesh& m = s.meshes[o.mesh];
    f.positions.resize(m.positions.size());
    f.normals.resize(m.normals.size());
    f.tangents.resize(m.tangents.size());
    parallelRange(m.positions.size(), [&](size_t b, size_t e) {
      for (size_t v = b; v < e; ++v) {
        f.positions[v] = w.transformPoint(m.positions[v]);
        f.normals[v] = normalize(f.normalMatrix.transformVector(m.normals[v]));
        Vec4 tg = m.tangents[v];
        f.tangents[v] = Vec4(normalize(w.transformVector(tg.xyz())), tg.w);
      }
    });
    f.stepPositions.clear();
    f.stepNormals.clear();
    if (blurred) {
      const int n = std::max(motionSteps, 2);
      f.stepPositions.resize(size_t(n));
      f.stepNormals.resize(size_t(n));
      for (int k = 0; k < n; ++k)
        transformMesh(m, o.worldMatrix(t + (close - t) * float(k) / float(n - 1)),
                      f.stepPositions[size_t(k)], f.stepNormals[size_t(k)]);
    }
    f.bounds = Bounds3{};
    for (const Vec3& p : f.positions) f.bounds.extend(p);
    for (const auto& step : f.stepPositions)
      for (const Vec3& p : step) f.bounds.extend(p);
  }
  if (changed) geometryVersion = newVersion();
  if (staticChanged) staticVersion = newVersion();
}

}  // namespace tandem
