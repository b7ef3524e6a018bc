#include "scene/scene_camera.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace tandem {

namespace {

// How much of the model a distant viewer looking back along `toViewer` sees: the projected area
// of the surfaces facing it, sum A max(0, n.d), with double-sided surfaces counted from either
// side at half weight (a closed double-sided mesh scores as if one-sided). Occlusion is ignored:
// it rewards the view that shows the broad side of flat parts, which is what a model viewer wants.
struct VisibleArea {
  std::vector<Vec3> weightedNormals;  // n * area, world space
  std::vector<bool> twoSided;

  explicit VisibleArea(const Scene& s) {
    const size_t total = s.triangleCount();
    // A sample of at most ~200k triangles is plenty for a ranking of views.
    const size_t stride = std::max<size_t>(1, total / 200000);
    size_t k = 0;
    for (const Object& o : s.objects) {
      const Mesh& m = s.meshes[size_t(o.mesh)];
      const Mat4 w = o.worldMatrix(0.0f);
      const bool two = s.materials[size_t(o.material)].doubleSided;
      for (size_t t = 0; t < m.triangleCount(); ++t, ++k) {
        if (k % stride) continue;
        Vec3 a = w.transformPoint(m.positions[m.indices[3 * t]]);
        Vec3 b = w.transformPoint(m.positions[m.indices[3 * t + 1]]);
        Vec3 c = w.transformPoint(m.positions[m.indices[3 * t + 2]]);
        Vec3 n = cross(b - a, c - a) * 0.5f;
        if (!std::isfinite(n.x + n.y + n.z)) continue;
        weightedNormals.push_back(n);
        twoSided.push_back(two);
      }
    }
  }
  double from(Vec3 toViewer) const {
    double sum = 0;
    for (size_t i = 0; i < weightedNormals.size(); ++i) {
      const float d = dot(weightedNormals[i], toViewer);
      sum += twoSided[i] ? 0.5 * std::abs(d) : std::max(d, 0.0f);
    }
    return sum;
  }
};

}  // namespace

Vec3 autoViewDirection(const Scene& s) {
  // The model viewer's default: in front (+Z), slightly above. Another view must show a quarter
  // more of the model to win, so ordinary models keep the familiar framing while flat ones
  // (a plane at x = const, a floor plan) are seen face-on rather than edge-on.
  const Vec3 preferred = normalize(Vec3(0.0f, 0.3f, 2.2f));
  VisibleArea area(s);
  if (area.weightedNormals.empty()) return preferred;
  Vec3 best = preferred;
  double bestScore = area.from(preferred) * 1.25;
  // Candidates on a Fibonacci sphere, elevation limited to [-30, 75] degrees so "up" stays up.
  const int n = 128;
  const float golden = 2.39996323f;
  for (int i = 0; i < n; ++i) {
    const float y = 1.0f - 2.0f * (float(i) + 0.5f) / float(n);
    if (y < -0.5f || y > 0.966f) continue;
    const float r = std::sqrt(std::max(0.0f, 1.0f - y * y));
    const Vec3 d(r * std::sin(golden * float(i)), y, r * std::cos(golden * float(i)));
    const double score = area.from(d);
    if (score > bestScore) bestScore = score, best = d;
  }
  return best;
}

CameraDesc defaultCamera(const Scene& s) {
  CameraDesc c = s.camera;
  if (!s.hasCamera) {
    Bounds3 b = s.bounds();
    Vec3 centre = b.center();
    float radius = std::max(length(b.extent()) * 0.5f, 1e-3f);
    c.lookAt = centre;
    // Far enough that the bounding sphere fits the vertical field of view (the narrower one for
    // landscape images), so tall models are not cut off.
    const float halfFov = radians(std::clamp(c.vfovDeg, 1.0f, 179.0f)) * 0.5f;
    c.position = centre + autoViewDirection(s) * (radius / std::sin(halfFov));
    c.nearPlane = std::max(radius * 1e-3f, 1e-5f);
  }
  fitNearPlane(c);
  return c;
}

StereoDesc fitStereoToModel(const Scene& s, const CameraDesc& c, StereoDesc st, bool ipdGiven) {
  if (!st.enabled || s.hasCamera || ipdGiven) return st;
  const Bounds3 b = s.bounds();
  const float nearest =
      length(c.position - b.center()) - std::max(length(b.extent()) * 0.5f, 1e-3f);
  st.ipd = std::min(st.ipd, std::max(nearest, 1e-4f) / 30.0f);
  return st;
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
