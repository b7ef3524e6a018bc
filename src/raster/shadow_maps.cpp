#include "raster/shadow_maps.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "raster/visibility_buffer.h"

namespace tandem {

namespace {

Vec3 anyUp(Vec3 dir) {
  return std::abs(dir.y) < 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
}

uint64_t nextVersion() {
  static std::atomic<uint64_t> next{1};
  return next++;
}

std::vector<float> lightKey(const Scene& s) {
  std::vector<float> k;
  for (const Light& l : s.lights)
    k.insert(k.end(),
             {float(l.type), l.position.x, l.position.y, l.position.z, l.direction.x, l.direction.y,
              l.direction.z, l.outerConeDeg, l.range, l.castsShadows ? 1.0f : 0.0f});
  return k;
}

}  // namespace

bool solidCaster(const Material& m) {
  const Vec3 through =
      (Vec3(1.0f) - vmin(m.diffuse, Vec3(1.0f))) * (1.0f - m.opacity) * m.transmissionFilter;
  return m.castsShadows && (through.x + through.y + through.z) / 3.0f < 0.5f;
}

std::vector<uint8_t> ShadowMaps::solidOf(const std::vector<uint8_t>& casters) const {
  std::vector<uint8_t> out(casters.size(), 0);
  for (size_t o = 0; o < casters.size(); ++o)
    out[o] = casters[o] && o < solidCaster_.size() && solidCaster_[o] ? 1 : 0;
  return out;
}

bool cubeShadowMap(const Light& l) {
  return l.type != LightType::Directional && !(l.type == LightType::Spot && l.outerConeDeg < 80.0f);
}

int shadowFaceSize(const Light& l, int resolution) {
  if (l.type == LightType::Directional) return 2 * resolution;
  return cubeShadowMap(l) ? std::max(resolution / 2, 16) : resolution;
}

int budgetedShadowMapSize(const Scene& scene, int requested) {
  // In maps of `requested` texels a side; a cube's six faces count in full (their texels and
  // the lookups' companions), a directional map as the four it holds.
  double faces = 0;
  for (const Light& l : scene.lights)
    if (l.castsShadows)
      faces += cubeShadowMap(l) ? 6.0 : l.type == LightType::Directional ? 4.0 : 1.0;
  if (faces == 0) return requested;
  const int fit = int(std::sqrt(kMaxShadowTexels / faces)) / 32 * 32;
  return std::min(requested, std::max(fit, 32));
}

void ShadowMaps::update(const FrameScene& fs, int requested, const std::vector<uint8_t>* wanted) {
  const Scene& scene = *fs.scene;
  const int resolution = budgetedShadowMapSize(scene, requested);
  std::vector<float> key = lightKey(scene);
  const bool staticStale = fs.staticVersion != staticVersion_ || key != lightKey_ ||
                           resolution != resolution_ || fs.scene != scene_;
  const bool geometryMoved = fs.geometryVersion != geometryVersion_ || fs.motionBlur() != sweep_;
  // The lights to draw now: every wanted one after a full redraw, else those wanted for the
  // first time (lights come into view). Maps of lights no longer wanted stay until the next full
  // redraw: the texel budget already counts them.
  const size_t n = scene.lights.size();
  auto isWanted = [&](size_t i) {
    return scene.lights[i].castsShadows && (!wanted || (i < wanted->size() && (*wanted)[i]));
  };
  faces_.resize(n);
  std::vector<size_t> fresh;
  for (size_t i = 0; i < n; ++i) {
    if (isWanted(i) && (staticStale || faces_[i].empty())) fresh.push_back(i);
    if (staticStale && !isWanted(i)) faces_[i].clear();
  }
  if (!staticStale && fresh.empty() && !geometryMoved) return;
  version_ = nextVersion();
  sweep_ = fs.motionBlur();
  geometryVersion_ = fs.geometryVersion;
  staticVersion_ = fs.staticVersion;
  scene_ = fs.scene;
  lightKey_ = std::move(key);
  resolution_ = resolution;
  casts_.assign(n, 0);
  for (size_t i = 0; i < n; ++i) casts_[i] = scene.lights[i].castsShadows ? 1 : 0;
  // Casters that are not animated are drawn once; animated ones each time they moved, over a
  // copy of the static depth.
  std::vector<uint8_t> moving(scene.objects.size()), still(scene.objects.size());
  bool anyMoving = false;
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    moving[o] = scene.objects[o].animated() ? 1 : 0;
    still[o] = 1 - moving[o];
    anyMoving |= moving[o] != 0;
  }
  opaqueCaster_.assign(scene.objects.size(), 0);
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const Material& m = scene.materials[size_t(scene.objects[o].material)];
    opaqueCaster_[o] = m.castsShadows && m.opacity >= 1.0f && m.alphaMode == AlphaMode::Opaque &&
                       (!sweep_ || fs.objects[o].stepPositions.empty());
  }
  solidCaster_.assign(scene.objects.size(), 0);
  for (size_t o = 0; o < scene.objects.size(); ++o)
    solidCaster_[o] = solidCaster(scene.materials[size_t(scene.objects[o].material)]) ? 1 : 0;
  if (staticStale) ++redraws_;
  std::vector<ShadowMapDevice::Job> jobs;
  std::vector<ShadowMapDevice::Job>* deviceJobs = device_ ? &jobs : nullptr;
  if (!fresh.empty()) drawStatic(fs, still, anyMoving, fresh, deviceJobs);
  mapped_ = 0;
  for (const std::vector<Face>& faces : faces_) mapped_ += faces.empty() ? 0 : 1;
  if (!anyMoving) {
    if (device_) device_->draw(fs, jobs, false, sweep_, opaqueCaster_, solidCaster_);
    return;
  }
  ++movingRedraws_;
  // Only where the moving casters are now or were last time: the rest of each map is the
  // static casters' as drawn once. A face neither sees is left alone. Without new geometry
  // only the lights drawn just now need their moving casters.
  std::vector<Bounds3> boxes;
  for (size_t o = 0; o < scene.objects.size(); ++o)
    if (moving[o]) boxes.push_back(fs.objects[o].bounds);
  std::vector<size_t> lights = fresh;
  if (staticStale || geometryMoved) {
    lights.clear();
    for (size_t i = 0; i < n; ++i) lights.push_back(i);
  }
  const std::vector<uint8_t> movingSolid = solidOf(moving);
  std::vector<Face*> all;
  for (const size_t i : lights)
    for (size_t k = 0; k < faces_[i].size(); ++k) {
      Face& face = faces_[i][k];
      const TexelRect now = footprint(face, boxes);
      const TexelRect dirty = now.unite(face.moving);
      if (dirty.empty()) continue;
      face.moving = now;
      if (device_) {
        ShadowMapDevice::Job job{i,        k,        face.camera, {},   dirty.x0,
                                 dirty.y0, dirty.x1, dirty.y1,    false};
        if (!now.empty()) job.casters = moving;
        jobs.push_back(std::move(job));
        continue;
      }
      restoreStatic(face, dirty);
      if (!now.empty())
        raster_.render(fs, face.camera, face.map,
                       Rasterizer::Subset{&movingSolid, /*keep=*/true, /*bothFaces=*/true});
      face.dirty = dirty;
      all.push_back(&face);
    }
  if (device_) {
    device_->draw(fs, jobs, true, sweep_, opaqueCaster_, solidCaster_);
    return;
  }
  tbb::parallel_for(size_t(0), all.size(), [&](size_t k) {
    Face& face = *all[k];
    if (!face.moving.empty())
      drawConservativeDepth(fs, face.camera, &moving, /*keep=*/true, sweep_, face.near);
    markOpaque(face, face.dirty);
  });
}

ShadowMaps::TexelRect ShadowMaps::footprint(const Face& f, const std::vector<Bounds3>& boxes) {
  const Camera& c = f.camera;
  const bool perspective = c.desc.projection == Projection::Perspective;
  const int width = c.width, height = c.height;
  const TexelRect whole{0, 0, width, height};
  TexelRect r;
  float lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (const Bounds3& b : boxes)
    for (int k = 0; k < 8; ++k) {
      const Vec3 p{k & 1 ? b.hi.x : b.lo.x, k & 2 ? b.hi.y : b.lo.y, k & 4 ? b.hi.z : b.lo.z};
      if (perspective && dot(p - c.desc.position, c.forward) <= c.desc.nearPlane)
        return whole;  // around or behind the light: the whole face, to be safe
      const Vec4 q = c.viewProj * Vec4(p, 1.0f);
      const float sx = (q.x / q.w * 0.5f + 0.5f) * float(width);
      const float sy = (0.5f - q.y / q.w * 0.5f) * float(height);
      lo[0] = std::min(lo[0], sx), hi[0] = std::max(hi[0], sx);
      lo[1] = std::min(lo[1], sy), hi[1] = std::max(hi[1], sy);
    }
  if (!(hi[0] >= lo[0])) return r;  // no boxes
  // Two texels of margin: conservative drawing touches partly covered texels.
  r.x0 = std::clamp(int(std::floor(lo[0])) - 2, 0, width);
  r.y0 = std::clamp(int(std::floor(lo[1])) - 2, 0, height);
  r.x1 = std::clamp(int(std::ceil(hi[0])) + 2, 0, width);
  r.y1 = std::clamp(int(std::ceil(hi[1])) + 2, 0, height);
  return r;
}

void ShadowMaps::restoreStatic(Face& f, const TexelRect& r) {
  for (int y = r.y0; y < r.y1; ++y) {
    const size_t a = size_t(y) * size_t(f.map.width) + size_t(r.x0), n = size_t(r.x1 - r.x0);
    std::copy_n(f.staticDepth.begin() + std::ptrdiff_t(a), n,
                f.map.depth.begin() + std::ptrdiff_t(a));
    std::copy_n(f.staticObject.begin() + std::ptrdiff_t(a), n,
                f.map.object.begin() + std::ptrdiff_t(a));
    std::copy_n(f.staticNear.texels.begin() + std::ptrdiff_t(a), n,
                f.near.texels.begin() + std::ptrdiff_t(a));
  }
}

void ShadowMaps::drawOn(std::unique_ptr<ShadowMapDevice> device) {
  device_ = std::move(device);
  invalidate();
}

void ShadowMaps::invalidate() {
  staticVersion_ = ~0ull;
  geometryVersion_ = ~0ull;
  for (std::vector<Face>& faces : faces_) faces.clear();
}

void ShadowMaps::drawStatic(const FrameScene& fs, const std::vector<uint8_t>& still, bool keepCopy,
                            const std::vector<size_t>& lights,
                            std::vector<ShadowMapDevice::Job>* jobs) {
  const Scene& scene = *fs.scene;
  // The directional maps cover the scene's bounds as they are now (a moving caster that
  // leaves them later casts no fallback shadow outside).
  const Bounds3 b = scene.bounds(fs.time);
  const Vec3 centre = (b.lo + b.hi) * 0.5f;
  const float radius = std::max(0.5f * length(b.hi - b.lo), 0.01f);
  // Maps keep their memory from one redraw to the next.
  std::vector<Face*> all;
  std::vector<const std::vector<uint8_t>*> drawn;  // per face in `all`: the casters drawn
  std::vector<std::vector<uint8_t>> inRange(scene.lights.size());
  for (const size_t i : lights) {
    const Light& l = scene.lights[i];
    // A light with a range lights nothing beyond it, and a caster can only block it between
    // the light and a point it lights, inside the range's sphere: casters outside stay undrawn.
    const std::vector<uint8_t>* casters = &still;
    if (l.type != LightType::Directional && l.range > 0 && std::isfinite(l.range)) {
      std::vector<uint8_t>& mask = inRange[i];
      mask = still;
      const float reach = l.range * 1.01f;  // a margin for the texels' spread of directions
      for (size_t o = 0; o < mask.size(); ++o) {
        const Bounds3& ob = fs.objects[o].bounds;
        const Vec3 nearest = vmin(vmax(l.position, ob.lo), ob.hi);
        if (length(nearest - l.position) > reach) mask[o] = 0;
      }
      casters = &mask;
    }
    const std::vector<uint8_t> solid = jobs ? std::vector<uint8_t>() : solidOf(*casters);
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
      const bool spot = !cubeShadowMap(l);
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
    // (shadowFaceSize: a cube's faces at half the side, a directional map at twice.)
    const int size = shadowFaceSize(l, resolution_);
    faces_[i].resize(views.size());
    for (size_t k = 0; k < views.size(); ++k) {
      Face& face = faces_[i][k];
      face.camera = Camera::make(views[k], size, size);
      face.texelPerDistance = face.camera.desc.projection == Projection::Perspective
                                  ? 2.0f * face.camera.tanHalfFov / float(size)
                                  : face.camera.desc.orthoHeight / float(size);
      face.moving = {};  // the maps hold no moving caster now
      if (jobs) {
        jobs->push_back({i, k, face.camera, *casters, 0, 0, size, size, true});
        continue;
      }
      raster_.render(fs, face.camera, face.map,
                     Rasterizer::Subset{&solid, /*keep=*/false, /*bothFaces=*/true});
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
      if (keepCopy) {
        face.staticDepth = face.map.depth;
        face.staticObject = face.map.object;
      } else {
        face.staticDepth.clear();
        face.staticObject.clear();
      }
      all.push_back(&face);
      drawn.push_back(casters);
    }
  }
  tbb::parallel_for(size_t(0), all.size(), [&](size_t k) {
    Face& face = *all[k];
    drawConservativeDepth(fs, face.camera, drawn[k], /*keep=*/false, sweep_, face.near);
    if (keepCopy) face.staticNear = face.near;
    markOpaque(face, {0, 0, face.map.width, face.map.height});
  });
}

std::vector<ShadowMaps::FaceView> ShadowMaps::faceViews(size_t i) const {
  std::vector<FaceView> out;
  if (i >= faces_.size()) return out;
  for (const Face& f : faces_[i])
    out.push_back({&f.camera, f.camera.width, f.camera.height, f.texelPerDistance,
                   f.map.depth.empty() ? nullptr : f.map.depth.data(),
                   f.near.texels.empty() ? nullptr : f.near.texels.data(),
                   f.opaqueDepth.empty() ? nullptr : f.opaqueDepth.data()});
  return out;
}

const ShadowMaps::Face* ShadowMaps::faceFor(size_t i, Vec3 p) const {
  if (i >= faces_.size() || faces_[i].empty()) return nullptr;
  const std::vector<Face>& faces = faces_[i];
  if (faces.size() != 6) return &faces[0];
  return &faces[size_t(cubeFace(p - faces[0].camera.desc.position))];
}

void ShadowMaps::markOpaque(Face& face, const TexelRect& r) const {
  face.opaqueDepth.resize(face.map.depth.size());
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      const size_t k = size_t(y) * size_t(face.map.width) + size_t(x);
      const uint32_t o = face.map.object[k];
      const bool opaque = o != kNoObject && o < opaqueCaster_.size() && opaqueCaster_[o];
      face.opaqueDepth[k] = opaque ? face.map.depth[k] : 0.0f;
    }
}

ShadowClass ShadowMaps::classify(size_t i, Vec3 p, Vec3 n, int self) const {
  ShadowClass c = ShadowClass::Traced;
  const bool want = true;
  classify(i, 1, &p, &n, &self, &want, &c);
  return c;
}

void ShadowMaps::classify(size_t i, int count, const Vec3* p, const Vec3* nrm, const int* self,
                          const bool* want, ShadowClass* out) const {
  // Two sweeps over the lanes: the first works out every lane's texel and asks for its cache
  // line, the second reads them (the maps are far larger than the caches). A caster of
  // reversed-Z depth d lies more than a gap nearer the light than p when d * a > b, with (a, b)
  // worked out per lane and gap: no division per tap.
  struct Limit {
    float a = 0, b = 1;  // never met by d <= 1
    bool met(float d) const { return d * a > b; }
  };
  struct Lane {
    const Face* face = nullptr;
    float sx, sy;
    Limit own, other, shadow;
  };
  Lane lanes[8];
  count = std::min(count, 8);
  for (int k = 0; k < count; ++k) {
    if (!want[k]) continue;
    out[k] = ShadowClass::Traced;
    const Face* f = faceFor(i, p[k]);
    if (!f) {
      // The light casts no shadows; or it does and was not wanted this frame: a ray decides.
      if (i >= casts_.size() || !casts_[i]) out[k] = ShadowClass::Lit;
      continue;
    }
    const Camera& c = f->camera;
    const bool perspective = c.desc.projection == Projection::Perspective;
    const Vec3 rel = p[k] - c.desc.position;
    const float along = dot(rel, c.forward);
    if (perspective && along <= c.desc.nearPlane) continue;
    // Cosine between the normal and the light: n.rel / |rel| (perspective), n.forward (ortho).
    const float nr = perspective ? dot(nrm[k], rel) : dot(nrm[k], c.forward);
    const float r2 = perspective ? dot(rel, rel) : 1.0f;
    if (nr * nr < 0.01f * r2) continue;  // grazing (cosine < 0.1): the slope swamps the map
    const float texel = perspective ? along * f->texelPerDistance : f->texelPerDistance;
    // How much nearer than p the receiver's own surface may lie within p's texel (its slope
    // over the texel's diagonal, plus a texel for curvature).
    const float tangent = std::sqrt(std::max(r2 - nr * nr, 0.0f)) / std::abs(nr);
    const float slope = texel * (1.4143f * tangent + 1.0f);
    const float farPlane = c.desc.farPlane, nearPlane = c.desc.nearPlane;
    auto limit = [&](float gap) {
      const float z = along - gap;
      if (perspective) return z > nearPlane ? Limit{z, nearPlane} : Limit{};
      return Limit{farPlane - nearPlane, farPlane - z};
    };
    const Mat4& m = c.viewProj;
    const Vec3 q = p[k];
    const float w =
        perspective ? m.m[3][0] * q.x + m.m[3][1] * q.y + m.m[3][2] * q.z + m.m[3][3] : 1.0f;
    if (perspective && w <= 1e-8f) continue;
    const float iw = 1.0f / w;
    Lane& l = lanes[k];
    l.sx = ((m.m[0][0] * q.x + m.m[0][1] * q.y + m.m[0][2] * q.z + m.m[0][3]) * iw * 0.5f + 0.5f) *
           float(f->map.width);
    l.sy = (0.5f - (m.m[1][0] * q.x + m.m[1][1] * q.y + m.m[1][2] * q.z + m.m[1][3]) * iw * 0.5f) *
           float(f->map.height);
    if (!(l.sx >= 1 && l.sy >= 1 && l.sx < float(f->map.width - 1) &&
          l.sy < float(f->map.height - 1)))
      continue;  // outside the map (or NaN): no certainty
    l.face = f;
    l.own = limit(slope);
    // Another object counts from the shadow ray's own start offset on (offsetRayOrigin).
    l.other = limit(1e-4f * (1.0f + maxComponent(vmax(q, -q))));
    l.shadow = limit(slope + 2.0f * texel);
    __builtin_prefetch(&f->near.texels[size_t(l.sy) * size_t(f->near.width) + size_t(l.sx)]);
  }
  for (int k = 0; k < count; ++k) {
    const Lane& l = lanes[k];
    if (!want[k] || !l.face) continue;
    const Face& f = *l.face;
    // Lit: the shadow ray projects onto p's texel (and, within rounding, its neighbours); no
    // caster touching those texels is nearer than p, beyond the receiver's own slope.
    const float e = 0.02f;
    const int tx0 = int(l.sx - e), tx1 = int(l.sx + e), ty0 = int(l.sy - e), ty1 = int(l.sy + e);
    bool blocked = false;
    for (int y = ty0; y <= ty1; ++y)
      for (int x = tx0; x <= tx1; ++x) {
        const ConservativeDepth::Texel& t =
            f.near.texels[size_t(y) * size_t(f.near.width) + size_t(x)];
        blocked |= (int(t.object) == self[k] ? l.own : l.other).met(t.depth);
      }
    if (!blocked) {
      out[k] = ShadowClass::Lit;
      continue;
    }
    // Shadowed: every texel centre around p holds an opaque static caster well in front of it.
    const int cx = int(l.sx), cy = int(l.sy);
    bool shadowed = true;
    for (int y = cy - 1; y <= cy + 1 && shadowed; ++y) {
      const float* row = &f.opaqueDepth[size_t(y) * size_t(f.map.width) + size_t(cx - 1)];
      shadowed = l.shadow.met(row[0]) && l.shadow.met(row[1]) && l.shadow.met(row[2]);
    }
    if (shadowed) out[k] = ShadowClass::Shadowed;
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
    face[k] = -1;  // (lanes not asked about need no face)
    if (!(use[k] > 0)) continue;
    face[k] = cubeFace({px[k] - l.x, py[k] - l.y, pz[k] - l.z});
    seen |= 1u << face[k];
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
