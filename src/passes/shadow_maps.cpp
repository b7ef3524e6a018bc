#include "passes/shadow_maps.h"

#include <cmath>

namespace tandem {

namespace {

Vec3 anyUp(Vec3 dir) {
  return std::abs(dir.y) < 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
}

// Distance along the map camera's axis of a stored reversed-Z depth.
float axisDistance(const Camera& c, float depth) {
  if (c.desc.projection == Projection::Perspective) return c.desc.nearPlane / depth;
  return c.desc.farPlane - depth * (c.desc.farPlane - c.desc.nearPlane);
}

std::vector<float> lightKey(const Scene& s) {
  std::vector<float> k;
  for (const Light& l : s.lights)
    k.insert(k.end(), {float(l.type), l.position.x, l.position.y, l.position.z, l.direction.x,
                       l.direction.y, l.direction.z, l.outerConeDeg, l.castsShadows ? 1.0f : 0.0f});
  return k;
}

}  // namespace

void ShadowMaps::update(const FrameScene& fs, int resolution) {
  const Scene& scene = *fs.scene;
  std::vector<float> key = lightKey(scene);
  if (fs.geometryVersion == geometryVersion_ && key == lightKey_ && resolution == resolution_)
    return;
  geometryVersion_ = fs.geometryVersion;
  lightKey_ = std::move(key);
  resolution_ = resolution;
  ++redraws_;
  const Bounds3 b = scene.bounds(fs.time);
  const Vec3 centre = (b.lo + b.hi) * 0.5f;
  const float radius = std::max(0.5f * length(b.hi - b.lo), 0.01f);
  // Maps keep their memory from one redraw to the next (animated scenes redraw every frame).
  faces_.resize(scene.lights.size());
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    if (!l.castsShadows) {
      faces_[i].clear();
      continue;
    }
    std::vector<CameraDesc> views;
    if (l.type == LightType::Directional) {
      CameraDesc c;
      c.projection = Projection::Orthographic;
      c.position = centre - l.direction * (radius + 1.0f);
      c.lookAt = centre;
      c.up = anyUp(l.direction);
      c.orthoHeight = 2.0f * radius;
      c.nearPlane = 0.01f;
      c.farPlane = 2.0f * radius + 2.0f;
      views.push_back(c);
    } else {
      const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
      const bool spot = l.type == LightType::Spot && l.outerConeDeg < 80.0f;
      for (int f = 0; f < (spot ? 1 : 6); ++f) {
        const Vec3 dir = spot ? l.direction : axes[f];
        CameraDesc c;
        c.position = l.position;
        c.lookAt = l.position + dir;
        c.up = anyUp(dir);
        // A cube face spans 90 degrees; a little more so that PCF taps at its edge stay inside.
        c.vfovDeg = spot ? std::min(2.0f * l.outerConeDeg + 2.0f, 170.0f) : 92.0f;
        c.nearPlane = 0.05f;
        views.push_back(c);
      }
    }
    // Cube faces at half the size: six of them cover what one map does for a spot.
    const int size = views.size() == 6 ? std::max(resolution / 2, 16) : resolution;
    faces_[i].resize(views.size());
    for (size_t k = 0; k < views.size(); ++k) {
      Face& face = faces_[i][k];
      face.camera = Camera::make(views[k], size, size);
      raster_.render(fs, face.camera, face.map);
    }
  }
}

float ShadowMaps::visibility(size_t i, Vec3 p, Vec3 n) const {
  if (i >= faces_.size() || faces_[i].empty()) return 1.0f;
  const std::vector<Face>& faces = faces_[i];
  size_t first = 0, last = faces.size();
  if (faces.size() == 6) {  // a cube: the face of the major axis, no search
    const Vec3 d = p - faces[0].camera.desc.position;
    const Vec3 a{std::abs(d.x), std::abs(d.y), std::abs(d.z)};
    first = a.x >= a.y && a.x >= a.z ? (d.x > 0 ? 0 : 1)
            : a.y >= a.z             ? (d.y > 0 ? 2 : 3)
                                     : (d.z > 0 ? 4 : 5);
    last = first + 1;
  }
  for (size_t k = first; k < last; ++k) {
    const Face& f = faces[k];
    // Offset along the normal against acne, scaled with the map's texel footprint.
    const Camera& c = f.camera;
    const float along = dot(p - c.desc.position, c.forward);
    if (c.desc.projection == Projection::Perspective && along <= c.desc.nearPlane) continue;
    const float texel = c.desc.projection == Projection::Perspective
                            ? 2.0f * along * c.tanHalfFov / float(f.map.width)
                            : c.desc.orthoHeight / float(f.map.width);
    const Vec3 q = p + n * (1.5f * texel);
    Vec2 px;
    if (!c.project(q, px)) continue;
    // 2x2 taps around the point: percentage-closer filtering at a quarter of 3x3's cost.
    const int cx = int(std::floor(px.x - 0.5f)), cy = int(std::floor(px.y - 0.5f));
    if (cx < -1 || cy < -1 || cx >= f.map.width || cy >= f.map.height) continue;
    const float dq = dot(q - c.desc.position, c.forward);
    const float bias = 2.0f * texel;
    int lit = 0, taps = 0;
    for (int dy = 0; dy <= 1; ++dy)
      for (int dx = 0; dx <= 1; ++dx) {
        const int x = std::clamp(cx + dx, 0, f.map.width - 1);
        const int y = std::clamp(cy + dy, 0, f.map.height - 1);
        const float d = f.map.depth[size_t(y) * size_t(f.map.width) + size_t(x)];
        ++taps;
        if (d <= 0.0f || dq <= axisDistance(c, d) + bias) ++lit;
      }
    return float(lit) / float(taps);
  }
  return 1.0f;
}

}  // namespace tandem
