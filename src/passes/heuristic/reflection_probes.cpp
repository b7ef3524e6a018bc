#include "passes/heuristic/reflection_probes.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/parallel.h"
#include "rt/whitted.h"
#include "shading/batch_shader.h"
#include "shading/surface_resolve.h"

namespace tandem {

namespace {

const Vec3 kAxes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

std::vector<float> lightKey(const Scene& s) {
  std::vector<float> k;
  for (const Light& l : s.lights)
    k.insert(k.end(), {float(l.type), l.position.x, l.position.y, l.position.z, l.direction.x,
                       l.direction.y, l.direction.z, l.color.x, l.color.y, l.color.z, l.intensity,
                       l.outerConeDeg, l.innerConeDeg, l.range});
  return k;
}

uint64_t nextVersion() {
  static std::atomic<uint64_t> next{1};
  return next++;
}

}  // namespace

ReflectionProbes::ProbeView ReflectionProbes::probe(size_t o) const {
  if (o >= probes_.size() || probes_[o].size == 0) return {};
  const Probe& p = probes_[o];
  return {p.size, p.centre, p.radius, p.cameras.data(), p.faces.empty() ? nullptr : p.faces.data()};
}

void ReflectionProbes::drawOn(std::unique_ptr<ProbeDevice> device) {
  device_ = std::move(device);
  invalidate();
}

int ReflectionProbes::update(const FrameScene& fs, const ShadingContext& shading,
                             const std::vector<uint8_t>& wanted, int size, int refresh,
                             size_t capacity) {
  const Scene& scene = *fs.scene;
  std::vector<float> key = lightKey(scene);
  if (key != lightKey_ || probes_.size() != scene.objects.size()) {
    probes_.assign(scene.objects.size(), Probe{});
    lightKey_ = std::move(key);
    version_ = nextVersion();
  }
  ++updates_;
  int drawn = 0;
  std::vector<size_t> stale;
  for (size_t o = 0; o < wanted.size() && o < probes_.size(); ++o) {
    Probe& p = probes_[o];
    if (wanted[o]) p.wanted = updates_;
    if (!wanted[o] || (p.size == size && !outdated(fs, p))) continue;
    if (p.size == size) {
      stale.push_back(o);
      continue;
    }
    draw(fs, shading, int(o), size, p);  // missing: drawn now
    ++drawn;
  }
  std::sort(stale.begin(), stale.end(),
            [&](size_t a, size_t b) { return probes_[a].drawn < probes_[b].drawn; });
  for (size_t k = 0; k < stale.size() && k < size_t(std::max(refresh, 0)); ++k, ++drawn)
    draw(fs, shading, int(stale[k]), size, probes_[stale[k]]);
  // Memory stays bounded however many objects a camera path has shown.
  std::vector<size_t> held;
  for (size_t o = 0; o < probes_.size(); ++o)
    if (probes_[o].size > 0) held.push_back(o);
  if (held.size() > capacity) {
    std::sort(held.begin(), held.end(),
              [&](size_t a, size_t b) { return probes_[a].wanted < probes_[b].wanted; });
    for (size_t k = 0; k < held.size() - capacity; ++k) {
      probes_[held[k]] = Probe{};
      if (device_) device_->release(int(held[k]));
    }
    version_ = nextVersion();
  }
  if (drawn > 0) version_ = nextVersion();
  return drawn;
}

bool ReflectionProbes::outdated(const FrameScene& fs, const Probe& p) {
  if (p.version == fs.geometryVersion) return false;
  if (p.staticVersion != fs.staticVersion) return true;
  // Half a texel at a face's centre (a face spans 90 degrees).
  const float halfTexel = 0.25f * kPi / float(std::max(p.size, 1));
  for (const auto& [object, then] : p.movers) {
    const Bounds3& now = fs.objects[size_t(object)].bounds;
    const float moved = std::max(length(now.lo - then.lo), length(now.hi - then.hi));
    const float distance =
        std::max(length(now.center() - p.centre) - 0.5f * length(now.hi - now.lo), p.radius);
    if (moved > halfTexel * distance) return true;
  }
  return false;
}

void ReflectionProbes::draw(const FrameScene& fs, const ShadingContext& shading, int object,
                            int size, Probe& p) {
  const Scene& scene = *fs.scene;
  const Bounds3& b = fs.objects[size_t(object)].bounds;
  p.version = fs.geometryVersion;
  p.drawn = updates_;
  p.size = size;
  p.centre = b.center();
  // The smallest sphere about that centre holding every vertex (a ball's own radius).
  float r2 = 0;
  for (const Vec3& v : fs.objects[size_t(object)].positions)
    r2 = std::max(r2, dot(v - p.centre, v - p.centre));
  p.radius = std::max(std::sqrt(r2), 1e-4f);
  p.cameras.resize(6);
  if (device_)
    p.faces.clear();
  else
    p.faces.assign(6, Buffer(size, size, 3));
  // The object does not see itself. Mirrors and clear glass are left out too: drawn by the one
  // shading function they would be near-black discs, where the ray would see what lies behind
  // or around them; without them the probe shows that.
  std::vector<uint8_t> others(fs.objects.size(), 1);
  others[size_t(object)] = 0;
  p.staticVersion = fs.staticVersion;
  p.movers.clear();
  for (size_t o = 0; o < others.size(); ++o) {
    const Material& m = scene.materials[size_t(scene.objects[o].material)];
    if (m.reflectivity > 0.5f || m.opacity < 0.5f) others[o] = 0;
    if (others[o] && scene.objects[o].animated())
      p.movers.push_back({int(o), fs.objects[o].bounds});
  }
  for (int f = 0; f < 6; ++f) {
    CameraDesc d;
    d.position = p.centre;
    d.lookAt = p.centre + kAxes[f];
    d.up = std::abs(kAxes[f].y) > 0.5f ? Vec3(0, 0, 1) : Vec3(0, 1, 0);
    d.vfovDeg = 90.0f;
    d.nearPlane = 1e-3f * p.radius;
    p.cameras[size_t(f)] = Camera::make(d, size, size);
  }
  if (device_) {
    device_->draw(fs, object, p.cameras.data(), size, others);
    return;
  }
  for (int f = 0; f < 6; ++f) {
    const Camera& cam = p.cameras[size_t(f)];
    raster_.render(fs, cam, vis_, Rasterizer::Subset{&others, false});
    Buffer& face = p.faces[size_t(f)];
    parallelRange(
        size_t(size),
        [&](size_t y0, size_t y1) {
          BatchShader shader(shading, face);
          for (int y = int(y0); y < int(y1); ++y)
            for (int x = 0; x < size; ++x) {
              const size_t i = size_t(y) * size_t(size) + size_t(x);
              Vec3 o, dir;
              cam.generateRay(float(x) + 0.5f, float(y) + 0.5f, o, dir);
              if (vis_.object[i] == kNoObject) {
                face.setRgb(x, y, scene.skyRadiance(dir));
                continue;
              }
              const SurfaceSample s =
                  resolveSurface(fs, int(vis_.object[i]), int(vis_.prim[i]), o, dir);
              shader.batch().set(shader.lane(), s, -dir);
              shader.push(x, y);
            }
        },
        8);
  }
}

Vec3 ReflectionProbes::lookup(const Scene& scene, int object, Vec3 d) const {
  if (object < 0 || size_t(object) >= probes_.size() || probes_[size_t(object)].size == 0)
    return scene.skyRadiance(d);
  const Probe& p = probes_[size_t(object)];
  const int f = cubeFace(d);
  Vec2 px;
  if (!p.cameras[size_t(f)].project(p.centre + d, px)) return scene.skyRadiance(d);
  // Bilinear within the face (edges clamp: the seam is a texel wide).
  const int n = p.size;
  const float fx = std::clamp(px.x - 0.5f, 0.0f, float(n - 1)),
              fy = std::clamp(px.y - 0.5f, 0.0f, float(n - 1));
  const int x0 = int(fx), y0 = int(fy), x1 = std::min(x0 + 1, n - 1), y1 = std::min(y0 + 1, n - 1);
  const float tx = fx - float(x0), ty = fy - float(y0);
  const Buffer& face = p.faces[size_t(f)];
  auto at = [&](int x, int y) { return face.rgb(x, y); };
  return (at(x0, y0) * (1 - tx) + at(x1, y0) * tx) * (1 - ty) +
         (at(x0, y1) * (1 - tx) + at(x1, y1) * tx) * ty;
}

Vec3 ReflectionProbes::lookupFrom(const Scene& scene, int object, Vec3 p, Vec3 d,
                                  const Bounds3& proxy) const {
  if (object < 0 || size_t(object) >= probes_.size() || probes_[size_t(object)].size == 0)
    return scene.skyRadiance(d);
  // The slab exit of p + s d from the box (p inside; outside: no correction).
  const float ps[3] = {p.x, p.y, p.z}, ds[3] = {d.x, d.y, d.z};
  const float lo[3] = {proxy.lo.x, proxy.lo.y, proxy.lo.z},
              hi[3] = {proxy.hi.x, proxy.hi.y, proxy.hi.z};
  float far = INFINITY;
  for (int k = 0; k < 3; ++k) {
    if (ps[k] < lo[k] || ps[k] > hi[k]) return lookup(scene, object, d);
    if (ds[k] > 0) far = std::min(far, (hi[k] - ps[k]) / ds[k]);
    if (ds[k] < 0) far = std::min(far, (lo[k] - ps[k]) / ds[k]);
  }
  if (!std::isfinite(far)) return lookup(scene, object, d);
  const Vec3 towards = p + d * far - probes_[size_t(object)].centre;
  const float len = length(towards);
  return lookup(scene, object, len > 0 ? towards / len : d);
}

Vec3 ReflectionProbes::exitDirection(int object, Vec3 p, Vec3 t, float eta, Vec3& exit) const {
  exit = p;
  if (object < 0 || size_t(object) >= probes_.size() || probes_[size_t(object)].size == 0) return t;
  const Probe& pr = probes_[size_t(object)];
  // The far intersection of p + s t with the bounding sphere.
  const Vec3 oc = p - pr.centre;
  const float bq = dot(oc, t), c = dot(oc, oc) - pr.radius * pr.radius;
  const float disc = bq * bq - c;
  if (disc < 0.0f) return t;
  const float s = -bq + std::sqrt(disc);
  if (!(s > 0.0f)) return t;
  exit = p + t * s;
  const Vec3 n = normalize(exit - pr.centre);  // outward
  Vec3 out;
  if (!refractDir(t, -n, eta, out)) out = normalize(t - (-n) * (2.0f * dot(t, -n)));
  return out;
}

}  // namespace tandem
