#include "passes/shadow_maps.h"

#include <algorithm>
#include <cmath>

namespace tandem {

namespace {

Vec3 anyUp(Vec3 dir) {
  return std::abs(dir.y) < 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
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
  const bool staticStale = fs.staticVersion != staticVersion_ || key != lightKey_ ||
                           resolution != resolution_ || fs.scene != scene_;
  if (!staticStale && fs.geometryVersion == geometryVersion_) return;
  geometryVersion_ = fs.geometryVersion;
  staticVersion_ = fs.staticVersion;
  scene_ = fs.scene;
  lightKey_ = std::move(key);
  resolution_ = resolution;
  // Casters that are not animated are drawn once; animated ones each time they moved, over a
  // copy of the static depth.
  std::vector<uint8_t> moving(scene.objects.size()), still(scene.objects.size());
  bool anyMoving = false;
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    moving[o] = scene.objects[o].animated() ? 1 : 0;
    still[o] = 1 - moving[o];
    anyMoving |= moving[o] != 0;
  }
  if (staticStale) drawStatic(fs, still, anyMoving);
  if (!anyMoving) return;
  ++movingRedraws_;
  for (std::vector<Face>& faces : faces_)
    for (Face& face : faces) {
      std::copy(face.staticDepth.begin(), face.staticDepth.end(), face.map.depth.begin());
      raster_.render(fs, face.camera, face.map,
                     Rasterizer::Subset{&moving, /*keep=*/true, /*bothFaces=*/true});
    }
}

void ShadowMaps::drawStatic(const FrameScene& fs, const std::vector<uint8_t>& still,
                            bool keepCopy) {
  const Scene& scene = *fs.scene;
  ++redraws_;
  // The directional maps cover the scene's bounds as they are now (a moving caster that
  // leaves them later casts no fallback shadow outside).
  const Bounds3 b = scene.bounds(fs.time);
  const Vec3 centre = (b.lo + b.hi) * 0.5f;
  const float radius = std::max(0.5f * length(b.hi - b.lo), 0.01f);
  // Maps keep their memory from one redraw to the next.
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
    const int size = views.size() == 6 ? std::max(resolution_ / 2, 16) : resolution_;
    faces_[i].resize(views.size());
    for (size_t k = 0; k < views.size(); ++k) {
      Face& face = faces_[i][k];
      face.camera = Camera::make(views[k], size, size);
      face.texelPerDistance = face.camera.desc.projection == Projection::Perspective
                                  ? 2.0f * face.camera.tanHalfFov / float(size)
                                  : face.camera.desc.orthoHeight / float(size);
      raster_.render(fs, face.camera, face.map,
                     Rasterizer::Subset{&still, /*keep=*/false, /*bothFaces=*/true});
      const Camera& c = face.camera;
      ShadowFace& lf = face.lookup;  // its depth pointer is taken at lookup time
      lf.width = face.map.width;
      lf.height = face.map.height;
      for (int r = 0; r < 3; ++r)
        for (int j = 0; j < 4; ++j) lf.row[r][j] = c.viewProj.m[r == 2 ? 3 : r][j];
      lf.eye = c.desc.position;
      lf.forward = c.forward;
      lf.texelPerDistance = face.texelPerDistance;
      lf.perspective = c.desc.projection == Projection::Perspective;
      lf.nearPlane = c.desc.nearPlane;
      lf.farPlane = c.desc.farPlane;
      if (keepCopy)
        face.staticDepth = face.map.depth;
      else
        face.staticDepth.clear();
    }
  }
}

void ShadowMaps::visibilityBatch(size_t i, const float* px, const float* py, const float* pz,
                                 const float* nx, const float* ny, const float* nz,
                                 const float* use, int count, float* out) const {
  if (i >= faces_.size() || faces_[i].empty()) {
    for (int k = 0; k < count; ++k)
      if (use[k] > 0) out[k] = 1.0f;
    return;
  }
  const std::vector<Face>& faces = faces_[i];
  auto lookup = [&](const Face& f, const float* lanes) {
    ShadowFace lf = f.lookup;
    lf.depth = f.map.depth.data();
    shadowLookupBatch(lf, px, py, pz, nx, ny, nz, lanes, size_t(count), out);
  };
  if (faces.size() != 6) {
    lookup(faces[0], use);
    return;
  }
  // A cube: each point's face is its major axis from the light; one kernel call per face seen.
  const Vec3 l = faces[0].camera.desc.position;
  int face[16];
  unsigned seen = 0;
  for (int k = 0; k < count; ++k) {
    face[k] = cubeFace({px[k] - l.x, py[k] - l.y, pz[k] - l.z});
    if (use[k] > 0) seen |= 1u << face[k];
  }
  for (int f = 0; f < 6; ++f) {
    if (!(seen & (1u << f))) continue;
    float mine[16] = {};
    for (int k = 0; k < count; ++k) mine[k] = use[k] > 0 && face[k] == f ? 1.0f : 0.0f;
    lookup(faces[size_t(f)], mine);
  }
}

float ShadowMaps::visibility(size_t i, Vec3 p, Vec3 n) const {
  if (i >= faces_.size() || faces_[i].empty()) return 1.0f;
  const std::vector<Face>& faces = faces_[i];
  size_t first = 0, last = faces.size();
  if (faces.size() == 6) {  // a cube: the face of the major axis, no search
    first = size_t(cubeFace(p - faces[0].camera.desc.position));
    last = first + 1;
  }
  for (size_t k = first; k < last; ++k) {
    const Face& f = faces[k];
    const Camera& c = f.camera;
    const bool perspective = c.desc.projection == Projection::Perspective;
    const float along = dot(p - c.desc.position, c.forward);
    if (perspective && along <= c.desc.nearPlane) continue;
    // Offset along the normal against acne, scaled with the map's texel footprint.
    const float texel = perspective ? along * f.texelPerDistance : f.texelPerDistance;
    const Vec3 q = p + n * (1.5f * texel);
    const Mat4& m = c.viewProj;
    const float w = m.m[3][0] * q.x + m.m[3][1] * q.y + m.m[3][2] * q.z + m.m[3][3];
    if (perspective && w <= 1e-8f) continue;
    const float iw = 1.0f / w;
    const float sx =
        ((m.m[0][0] * q.x + m.m[0][1] * q.y + m.m[0][2] * q.z + m.m[0][3]) * iw * 0.5f + 0.5f) *
        float(f.map.width);
    const float sy =
        (0.5f - (m.m[1][0] * q.x + m.m[1][1] * q.y + m.m[1][2] * q.z + m.m[1][3]) * iw * 0.5f) *
        float(f.map.height);
    // 2x2 taps around the point: percentage-closer filtering at a quarter of 3x3's cost.
    const int cx = int(std::floor(sx - 0.5f)), cy = int(std::floor(sy - 0.5f));
    if (cx < -1 || cy < -1 || cx >= f.map.width || cy >= f.map.height) continue;
    const float dq = dot(q - c.desc.position, c.forward);
    const float bias = 2.0f * texel;
    // A tap is lit when its surface lies no nearer than dq - bias along the axis: one threshold
    // in the map's reversed-Z depth instead of a distance per tap (depth falls with distance).
    float threshold;
    if (perspective)
      threshold = dq - bias > 0.0f ? c.desc.nearPlane / (dq - bias) : INFINITY;
    else
      threshold = (c.desc.farPlane + bias - dq) / (c.desc.farPlane - c.desc.nearPlane);
    const int x0 = std::clamp(cx, 0, f.map.width - 1), x1 = std::clamp(cx + 1, 0, f.map.width - 1);
    const int y0 = std::clamp(cy, 0, f.map.height - 1),
              y1 = std::clamp(cy + 1, 0, f.map.height - 1);
    const float* row0 = &f.map.depth[size_t(y0) * size_t(f.map.width)];
    const float* row1 = &f.map.depth[size_t(y1) * size_t(f.map.width)];
    auto litTap = [&](float d) { return d <= 0.0f || d <= threshold ? 1 : 0; };
    const int lit = litTap(row0[x0]) + litTap(row0[x1]) + litTap(row1[x0]) + litTap(row1[x1]);
    const int taps = 4;
    return float(lit) / float(taps);
  }
  return 1.0f;
}

}  // namespace tandem
