#include "rt/path_tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rt/whitted.h"
#include "scene/scene.h"
#include "shading/shade_batch.h"
#include "shading/surface_resolve.h"

namespace tandem {

namespace {

// The surface at a hit, from Embree's own distance and barycentrics.
SurfaceSample resolveHit(const FrameScene& fs, const Hit& h, Vec3 dir, float time) {
  const float tuv[3] = {h.t, h.u, h.v};
  return resolveSurface(fs, h.object, h.prim, Vec3(0.0f), dir, time, tuv);
}

// Unpolarised Fresnel reflectance of a dielectric; eta = n_incident / n_transmitted.
float fresnelDielectric(float cosi, float eta) {
  float sin2t = eta * eta * (1.0f - cosi * cosi);
  if (sin2t >= 1.0f) return 1.0f;  // total internal reflection
  float cost = std::sqrt(1.0f - sin2t);
  float rs = (eta * cosi - cost) / (eta * cosi + cost);
  float rp = (cosi - eta * cost) / (cosi + eta * cost);
  return 0.5f * (rs * rs + rp * rp);
}

Vec3 toWorld(Vec3 local, Vec3 n) {
  Vec3 t, b;
  orthonormalBasis(n, t, b);
  return t * local.x + b * local.y + n * local.z;
}

// Half vector with density (e + 1) / (2 pi) cos^e(theta_h) around n.
Vec3 sampleBlinnHalf(Vec3 n, float e, float u1, float u2) {
  float cosT = std::pow(u1, 1.0f / (e + 1.0f));
  float sinT = std::sqrt(std::max(0.0f, 1.0f - cosT * cosT)), phi = 2.0f * kPi * u2;
  return toWorld({sinT * std::cos(phi), sinT * std::sin(phi), cosT}, n);
}

float average(Vec3 v) {
  return (v.x + v.y + v.z) * (1.0f / 3.0f);
}

float powerHeuristic(float a, float b) {
  return a * a / (a * a + b * b);
}

// The BRDF (Lambert + normalised Blinn-Phong, what shadeBlinnPhong evaluates) and the density of
// the mixture the glossy lobe samples from (cosine with probability pd, else the Blinn-Phong
// half-vector lobe, per unit solid angle) for one pair of directions: both need the half vector
// and cos^e of its angle, computed once.
struct BrdfAndPdf {
  Vec3 f;
  float pdf;
};
BrdfAndPdf brdfAndPdf(Vec3 n, Vec3 wo, Vec3 wi, Vec3 kd, Vec3 ks, float pd, float e) {
  const float cosI = dot(n, wi);
  const bool glossy = maxComponent(ks) > 0.0f, lobe = cosI > 0.0f && pd < 1.0f;
  Vec3 h(0.0f);
  float cosPow = 0.0f;
  if (glossy || lobe) {
    h = normalize(wo + wi);
    cosPow = std::pow(std::max(dot(n, h), 0.0f), e);
  }
  BrdfAndPdf r;
  r.f = glossy ? kd * (1.0f / kPi) + ks * ((e + 8.0f) / (8.0f * kPi) * cosPow) : kd * (1.0f / kPi);
  if (cosI <= 0.0f)
    r.pdf = 0.0f;
  else if (pd >= 1.0f)  // Lambert only: no lobe to evaluate
    r.pdf = cosI / kPi;
  else
    r.pdf = pd * cosI / kPi +
            (1.0f - pd) * ((e + 1.0f) / (2.0f * kPi) * cosPow) / std::max(4.0f * dot(wo, h), 1e-6f);
  return r;
}

}  // namespace

Vec3 sampleCosine(Vec3 n, float u1, float u2) {
  float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
  return toWorld({r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u1))}, n);
}

EmitterTable::EmitterTable(const FrameScene& fs) : frame_(&fs) {
  const Scene& scene = *fs.scene;
  objectFirst_.assign(fs.objects.size(), -1);
  for (size_t o = 0; o < fs.objects.size(); ++o) {
    const Material& m = scene.materials[scene.objects[o].material];
    float lum = average(m.emission);
    if (!(lum > 0.0f)) continue;
    const Mesh& mesh = scene.meshes[scene.objects[o].mesh];
    const std::vector<Vec3>& p = fs.objects[o].positions;
    objectFirst_[o] = int(tris_.size());
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      const Vec3 a = p[mesh.indices[3 * t]], b = p[mesh.indices[3 * t + 1]],
                 c = p[mesh.indices[3 * t + 2]];
      // Rigid motion keeps the area, so the frame's triangle prices every shutter time.
      Tri tri{int(o), int(t), 0.5f * length(cross(b - a, c - a))};
      tris_.push_back(tri);
      weight_.push_back(tri.area * lum);
      total_ += double(tri.area * lum);
      cdf_.push_back(total_);
    }
  }
}

bool EmitterTable::sample(float u, Vec2 uv, float time, int& object, int& prim, Vec3& point,
                          float& pdf) const {
  if (empty()) return false;
  size_t i = size_t(std::lower_bound(cdf_.begin(), cdf_.end(), double(u) * total_) - cdf_.begin());
  i = std::min(i, tris_.size() - 1);
  const Tri& t = tris_[i];
  if (!(t.area > 0.0f)) return false;
  const FrameObject& fo = frame_->objects[size_t(t.object)];
  const Mesh& mesh = frame_->scene->meshes[frame_->scene->objects[size_t(t.object)].mesh];
  const uint32_t* idx = &mesh.indices[3 * size_t(t.prim)];
  float su = std::sqrt(uv.x);  // uniform on the triangle
  point = positionAt(fo, idx[0], time) * (1.0f - su) +
          positionAt(fo, idx[1], time) * (su * (1.0f - uv.y)) +
          positionAt(fo, idx[2], time) * (su * uv.y);
  object = t.object;
  prim = t.prim;
  pdf = float(weight_[i] / total_) / t.area;
  return true;
}

float EmitterTable::pdfArea(int object, int prim) const {
  if (empty() || object < 0 || size_t(object) >= objectFirst_.size() ||
      objectFirst_[size_t(object)] < 0)
    return 0.0f;
  const size_t i = size_t(objectFirst_[size_t(object)] + prim);
  if (i >= tris_.size() || !(tris_[i].area > 0.0f)) return 0.0f;
  return float(weight_[i] / total_) / tris_[i].area;
}

Vec3 PathTracer::areaLight(const SurfaceSample& s, Vec3 wo, Vec3 kd, Vec3 ks, float pd, float time,
                           SobolSampler& rng) const {
  int object, prim;
  Vec3 x;
  float pdfA;
  const float u = rng.uniform();
  if (!emitters_.sample(u, rng.get2D(), time, object, prim, x, pdfA)) return Vec3(0.0f);
  Vec3 toL = x - s.position;
  float dist = length(toL);
  if (!(dist > 0.0f)) return Vec3(0.0f);
  Vec3 wi = toL / dist;
  float cosI = dot(s.normal, wi);
  if (cosI <= 0.0f) return Vec3(0.0f);
  // One closest-hit ray both tests visibility and reads the emitter's (textured) emission.
  Ray r;
  r.origin = offsetRayOrigin(s, wi);
  r.dir = wi;
  r.tfar = dist * 1.001f + 1e-4f;
  r.time = time;
  Hit h = rt_.intersect(r);
  if (!h.valid() || h.object != object || h.prim != prim) return Vec3(0.0f);
  SurfaceSample e = resolveHit(*rt_.frame(), h, wi, time);
  // Emitters light their front side only (double-sided ones face every ray, see resolveSurface).
  float cosL = -dot(e.geoNormal, wi);
  if (!(cosL > 1e-6f)) return Vec3(0.0f);
  float pdfLight = pdfA * h.t * h.t / cosL;
  const BrdfAndPdf b = brdfAndPdf(s.normal, wo, wi, kd, ks, pd, s.specularExponent);
  return b.f * e.emission * (cosI * powerHeuristic(pdfLight, b.pdf) / pdfLight);
}

// Next-event estimation to every punctual light (delta lights cannot be hit by chance), with
// the same BRDF shadeBlinnPhong evaluates. (Tried: the shadow rays of up to 8 lights in one
// Embree packet, since they leave one point: 25 % slower than single rays on atrium.)
Vec3 PathTracer::directLight(const SurfaceSample& s, Vec3 wo, Vec3 kd, Vec3 ks, float time) const {
  Vec3 sum(0.0f);
  const Vec3 n = s.normal;
  const float e = s.specularExponent;
  // With many range-limited lights, only those that reach the point (the rest add exactly 0).
  thread_local std::vector<uint32_t> reaching;
  if (shading_.cull) {
    Bounds3 at;
    at.extend(s.position);
    lightsReaching(shading_, at, reaching);
  }
  const size_t count = shading_.cull ? reaching.size() : scene_.lights.size();
  for (size_t j = 0; j < count; ++j) {
    const size_t i = shading_.cull ? reaching[j] : j;
    if (scene_.lights[i].fromEmissiveMesh) continue;  // its mesh's emission is hit instead
    LightSample ls = sampleLight(shading_.lights[i], s.position);
    float cosI = dot(n, ls.wi);
    if (cosI <= 0.0f || maxComponent(ls.radiance) <= 0.0f) continue;
    if (scene_.lights[i].castsShadows && rt_.occluded(shadowRayTowards(s, ls, time))) continue;
    sum += brdfAndPdf(n, wo, ls.wi, kd, ks, 1.0f, e).f * ls.radiance * cosI;
  }
  return sum;
}

Vec3 PathTracer::radiance(Vec3 o, Vec3 d, float time, SobolSampler& rng) const {
  Vec3 L(0.0f), beta(1.0f);
  // The BSDF density of the last bounce (0 after the camera or a specular bounce: emission
  // found then has no light-sampling counterpart and counts in full).
  float lastPdf = 0.0f;
  for (int depth = 0; depth < settings_.maxDepth; ++depth) {
    Ray ray;
    ray.origin = o;
    ray.dir = d;
    ray.time = time;
    // Camera rays cull the backs of single-sided surfaces, as the rasterizer does.
    Hit hit = rt_.intersect(ray, depth == 0);
    if (!hit.valid()) {
      L += beta * scene_.skyRadiance(d);
      break;
    }
    SurfaceSample s = resolveHit(*rt_.frame(), hit, d, time);
    // Emission leaves the front side only: a light's back (e.g. the Cornell lamp seen from the
    // 2 cm gap above it) is dark, as in pbrt and Mitsuba.
    if (maxComponent(s.emission) > 0.0f && dot(s.geoNormal, d) < 0.0f) {
      float w = 1.0f;
      if (lastPdf > 0.0f) {
        float cosL = -dot(s.geoNormal, d);
        float pdfLight =
            cosL > 1e-6f ? emitters_.pdfArea(hit.object, hit.prim) * hit.t * hit.t / cosL : 0.0f;
        w = powerHeuristic(lastPdf, pdfLight);
      }
      L += beta * s.emission * w;
    }
    lastPdf = 0.0f;
    const float t = 1.0f - s.opacity, m = (1.0f - t) * s.reflectivity;
    const float lobe = rng.uniform();
    Vec3 facing = dot(s.normal, d) > 0 ? -s.normal : s.normal;
    if (lobe < t) {
      // Fresnel dielectric: reflect with probability F, otherwise refract (weights cancel).
      bool entering = dot(s.geoNormal, d) < 0;
      float eta = entering ? scene_.environmentIor / s.ior : s.ior / scene_.environmentIor;
      Vec3 next;
      if (rng.uniform() < fresnelDielectric(-dot(d, facing), eta) ||
          !refractDir(d, facing, eta, next))
        next = reflectDir(d, facing);
      else if (s.material >= 0)  // what passes through is filtered (OBJ Tf)
        beta = beta * scene_.materials[size_t(s.material)].transmissionFilter;
      d = normalize(next);
    } else if (lobe < t + m) {
      d = normalize(reflectDir(d, facing));
    } else {
      // Lambert + normalised Blinn-Phong, shaded from whichever side the path arrives.
      Vec3 kd = vmax(s.diffuse, Vec3(0.0f)), ks = vmax(s.specular, Vec3(0.0f));
      float total = maxComponent(kd + ks);
      if (total > 1.0f) kd = kd / total, ks = ks / total;  // no energy created
      s.normal = facing;
      const Vec3 wo = -d;
      L += beta * directLight(s, wo, kd, ks, time);
      const float wd = average(kd), wsp = average(ks);
      if (wd + wsp <= 0.0f) break;
      const float pd = wd / (wd + wsp), e = s.specularExponent;
      if (!emitters_.empty()) L += beta * areaLight(s, wo, kd, ks, pd, time, rng);
      Vec3 wi;
      const float which = rng.uniform();
      const Vec2 u = rng.get2D();
      if (which < pd) {
        wi = sampleCosine(facing, u.x, u.y);
      } else {
        Vec3 h = sampleBlinnHalf(facing, e, u.x, u.y);
        wi = reflectDir(d, h);
      }
      const float cosI = dot(facing, wi);
      if (cosI <= 0.0f) break;
      // One-sample MIS over the two strategies: the mixture density.
      const BrdfAndPdf b = brdfAndPdf(facing, wo, wi, kd, ks, pd, e);
      const float pdf = b.pdf;
      if (!(pdf > 0.0f)) break;
      beta = beta * b.f * (cosI / pdf);
      d = normalize(wi);
      lastPdf = pdf;
    }
    o = offsetRayOrigin(s, d);
    if (depth + 1 >= settings_.rouletteDepth) {
      float q = std::min(maxComponent(beta), 0.95f);
      if (!(q > 0.0f) || rng.uniform() >= q) break;
      beta = beta / q;
    }
  }
  return L;
}

}  // namespace tandem
