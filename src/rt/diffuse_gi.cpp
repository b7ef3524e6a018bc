#include "rt/diffuse_gi.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rt/path_tracer.h"
#include "rt/whitted.h"
#include "scene/scene.h"
#include "shading/surface_resolve.h"

namespace tandem {

DiffuseGI::DiffuseGI(const RayTracer& rt, const Scene& scene, const ShadingContext& shading,
                     const LightGrid* grid)
    : rt_(rt), scene_(scene), shading_(shading), grid_(grid), lights_(lightsSampled(scene)) {}

std::vector<int> DiffuseGI::lightsSampled(const Scene& scene) {
  std::vector<int> lights;
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (!scene.lights[i].fromEmissiveMesh) lights.push_back(int(i));
  return lights;
}

LightGrid DiffuseGI::buildGrid(const Scene& scene, const ShadingContext& shading,
                               const RayTracer* rt) {
  LightGrid::Visibility visible;
  if (rt)
    visible = [&](Vec3 p, int i) {
      if (!scene.lights[size_t(i)].castsShadows) return true;
      const LightSample ls = sampleLight(shading.lights[size_t(i)], p);
      Ray r;
      r.origin = p;
      r.dir = ls.wi;
      r.tfar = std::isinf(ls.distance) ? std::numeric_limits<float>::infinity()
                                       : ls.distance * (1.0f - 1e-4f);
      return !rt->occluded(r);
    };
  return LightGrid(shading.lights, lightsSampled(scene), scene.bounds(), visible);
}

std::vector<std::string> DiffuseGI::blackMaterials(const Scene& scene) {
  std::vector<char> used(scene.materials.size(), 0);
  for (const Object& o : scene.objects) used[size_t(o.material)] = 1;
  std::vector<std::string> names;
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    const Material& mat = scene.materials[m];
    const bool metal = mat.metallicRoughnessTexture < 0 && mat.metallic >= 0.999f;
    const bool noDiffuse = maxComponent(mat.diffuse) <= 0.0f && mat.diffuseTexture < 0;
    if (used[m] && maxComponent(mat.emission) <= 0.0f && (metal || noDiffuse))
      names.push_back(mat.name);
  }
  return names;
}

std::string DiffuseGI::blackMaterialsNote(const Scene& scene) {
  const std::vector<std::string> names = blackMaterials(scene);
  if (names.empty()) return "";
  return std::to_string(names.size()) + " material(s) with no diffuse colour (e.g. '" +
         names.front() +
         "', a metal) draw black in the foveated path tracer and the diffuse-gi reference: "
         "their transport is Lambert only";
}

Vec3 DiffuseGI::albedo(const SurfaceSample& s) {
  return vmin(vmax(s.diffuse, Vec3(0.0f)), Vec3(1.0f));
}

Vec3 DiffuseGI::emitted(const SurfaceSample& s, Vec3 wo) {
  return dot(s.geoNormal, wo) > 0.0f ? s.emission : Vec3(0.0f);
}

Vec3 DiffuseGI::oneLight(const SurfaceSample& s, Vec3 n, float u, float time,
                         uint64_t& rays) const {
  if (lights_.empty()) return Vec3(0.0f);
  int i;
  float pdf;
  if (grid_) {
    const LightGrid::Pick pick = grid_->pick(s.position, u);
    if (pick.light < 0 || !(pick.pdf > 0.0f)) return Vec3(0.0f);
    i = pick.light;
    pdf = pick.pdf;
  } else {
    const int count = int(lights_.size());
    i = lights_[size_t(std::min(int(u * float(count)), count - 1))];
    pdf = 1.0f / float(count);
  }
  const LightSample ls = sampleLight(shading_.lights[size_t(i)], s.position);
  const float cosI = dot(n, ls.wi);
  if (cosI <= 0.0f || maxComponent(ls.radiance) <= 0.0f) return Vec3(0.0f);
  if (scene_.lights[size_t(i)].castsShadows) {
    ++rays;
    if (rt_.occluded(shadowRayTowards(s, ls, time))) return Vec3(0.0f);
  }
  return ls.radiance * (cosI / (pdf * kPi));
}

Vec3 DiffuseGI::reflected(const SurfaceSample& s, Vec3 wo, SobolSampler& rng, float time,
                          uint64_t& rays) const {
  // Double-sided: shade the side the viewer sees.
  const Vec3 n = dot(s.normal, wo) < 0.0f ? -s.normal : s.normal;
  const Vec2 u0 = rng.get2D(), u1 = rng.get2D(), u2 = rng.get2D();
  Vec3 sum = oneLight(s, n, u0.x, time, rays);
  // Cosine-weighted bounce: Lambert's cos / π cancels the density, leaving the incident radiance.
  Ray r;
  r.dir = normalize(sampleCosine(n, u1.x, u1.y));
  if (dot(r.dir, s.geoNormal) * dot(n, s.geoNormal) <= 0.0f) return sum;  // below the surface
  r.origin = offsetRayOrigin(s, r.dir);
  r.time = time;
  ++rays;
  const Hit h = rt_.intersect(r);
  if (!h.valid()) return sum + scene_.skyRadiance(r.dir);
  const float tuv[3] = {h.t, h.u, h.v};
  const SurfaceSample hs =
      resolveSurface(*rt_.frame(), h.object, h.prim, r.origin, r.dir, time, tuv);
  const Vec3 wh = -r.dir;
  const Vec3 nh = dot(hs.normal, wh) < 0.0f ? -hs.normal : hs.normal;
  return sum + emitted(hs, wh) + albedo(hs) * oneLight(hs, nh, u2.x, time, rays);
}

void DiffuseGI::considerLight(const SurfaceSample& s, Vec3 n, int i, size_t k,
                              std::vector<DirectCandidate>& out) const {
  const LightSample ls = sampleLight(shading_.lights[size_t(i)], s.position);
  const float cosI = dot(n, ls.wi);
  if (cosI <= 0.0f || maxComponent(ls.radiance) <= 0.0f) return;
  const DirectCandidate c{luminance(ls.radiance) * cosI, i, ls};
  // The brighter first, ties to the lower index: a strict order, so the best k of a set of lights
  // do not depend on the order they come in.
  auto better = [](const DirectCandidate& a, const DirectCandidate& b) {
    return a.luminance != b.luminance ? a.luminance > b.luminance : a.light < b.light;
  };
  if (out.size() == k && !better(c, out.back())) return;
  if (out.size() < k) out.push_back(c);
  size_t j = out.size() - 1;
  for (; j > 0 && better(c, out[j - 1]); --j) out[j] = out[j - 1];
  out[j] = c;
}

size_t DiffuseGI::brightestLights(const SurfaceSample& s, Vec3 n, int count,
                                  std::vector<DirectCandidate>& out) const {
  // The `count` best kept sorted as the lights go by (insertion: count is a handful, the lights
  // many).
  out.clear();
  const size_t k = size_t(std::max(count, 0));
  for (size_t i = 0; k > 0 && i < lights_.size(); ++i) considerLight(s, n, lights_[i], k, out);
  return out.size();
}

namespace {

// At least the luminance x cosine that light l can give any point of `box` (what brightestLights
// ranks by), with room for rounding; -1 where it gives none (beyond its range).
float scoreBound(const PreparedLight& l, const Bounds3& box) {
  if (std::min({l.power.x, l.power.y, l.power.z}) < 0.0f) return INFINITY;
  const float power = luminance(l.power);
  if (l.type == LightType::Directional) return power * 1.001f;
  if (std::min({l.attConstant, l.attLinear, l.attQuadratic}) < 0.0f) return INFINITY;
  // The nearest a point of the box can be: attenuation only falls with distance, and the
  // cosine and a spot's cone are at most 1.
  const Vec3 nearest = vmin(vmax(l.position, box.lo), box.hi);
  const float d = length(nearest - l.position) * 0.999f;
  if (l.range > 0 && d > l.range * 1.001f) return -1.0f;
  return 1.001f * power / std::max(l.attConstant + l.attLinear * d + l.attQuadratic * d * d, 1e-8f);
}

}  // namespace

Vec3 DiffuseGI::brightestDirect(const SurfaceSample& s, Vec3 wo, int count, float time,
                                uint64_t& rays) const {
  const Vec3 n = dot(s.normal, wo) < 0.0f ? -s.normal : s.normal;
  // Each light's unshadowed contribution (no ray yet); the `count` largest are traced.
  thread_local std::vector<DirectCandidate> candidates;  // no allocation per pixel
  const size_t k = brightestLights(s, n, count, candidates);
  Vec3 sum(0.0f);
  for (size_t c = 0; c < k; ++c) {
    const LightSample& ls = candidates[c].sample;
    if (scene_.lights[size_t(candidates[c].light)].castsShadows) {
      ++rays;
      if (rt_.occluded(shadowRayTowards(s, ls, time))) continue;
    }
    sum += ls.radiance * (dot(n, ls.wi) / kPi);
  }
  return sum;
}

void DiffuseGI::brightestDirect8(const SurfaceSample* s, const Vec3* wo, int n, int count,
                                 float time, Vec3* out, uint64_t& rays) const {
  thread_local std::vector<DirectCandidate> candidates[8];
  thread_local std::vector<float> bound;
  thread_local std::vector<uint32_t> order;
  Vec3 normal[8];
  const size_t want = size_t(std::max(count, 0));
  Bounds3 box;
  for (int j = 0; j < n; ++j) {
    normal[j] = dot(s[j].normal, wo[j]) < 0.0f ? -s[j].normal : s[j].normal;
    candidates[j].clear();
    out[j] = Vec3(0.0f);
    box.extend(s[j].position);
  }
  if (want == 0) return;
  // The lights that can give most to the box first: each surface's k-th best of them is a floor
  // no light bounded below it (for every surface) can beat, so those are never looked at. The
  // best k of the rest are what all the lights give (the order of a strict ranking).
  const size_t m = lights_.size(), first = std::min(want, m);
  bound.resize(m);
  order.resize(m);
  for (size_t i = 0; i < m; ++i) {
    bound[i] = scoreBound(shading_.lights[size_t(lights_[i])], box);
    order[i] = uint32_t(i);
  }
  std::partial_sort(order.begin(), order.begin() + ptrdiff_t(first), order.end(),
                    [&](uint32_t a, uint32_t b) { return bound[a] > bound[b]; });
  float floor = INFINITY;
  for (int j = 0; j < n; ++j) {
    for (size_t r = 0; r < first; ++r)
      considerLight(s[j], normal[j], lights_[order[r]], want, candidates[j]);
    floor = std::min(floor, candidates[j].size() == want ? candidates[j].back().luminance : 0.0f);
  }
  for (size_t r = first; r < m; ++r) {
    if (bound[order[r]] < floor || bound[order[r]] < 0.0f) continue;
    for (int j = 0; j < n; ++j)
      considerLight(s[j], normal[j], lights_[order[r]], want, candidates[j]);
  }
  size_t k[8] = {}, most = 0;
  for (int j = 0; j < n; ++j) most = std::max(most, k[j] = candidates[j].size());
  // Rank by rank, each surface's c-th brightest light in one packet: neighbouring pixels' rays
  // towards the same light are coherent. Each sum runs in rank order, as brightestDirect's.
  for (size_t c = 0; c < most; ++c) {
    Ray r[8];
    bool traced[8] = {}, blocked[8] = {};
    for (int j = 0; j < n; ++j) {
      if (c >= k[j] || !scene_.lights[size_t(candidates[j][c].light)].castsShadows) continue;
      r[j] = shadowRayTowards(s[j], candidates[j][c].sample, time);
      traced[j] = true;
      ++rays;
    }
    rt_.occluded8(r, traced, blocked);
    for (int j = 0; j < n; ++j) {
      if (c >= k[j] || blocked[j]) continue;
      const LightSample& ls = candidates[j][c].sample;
      out[j] += ls.radiance * (dot(normal[j], ls.wi) / kPi);
    }
  }
}

Vec3 DiffuseGI::radiance(const SurfaceSample& s, Vec3 wo, SobolSampler& rng, float time,
                         uint64_t& rays) const {
  return emitted(s, wo) + albedo(s) * reflected(s, wo, rng, time, rays);
}

}  // namespace tandem
