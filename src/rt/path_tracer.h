// Reference path tracing: unidirectional paths from the camera with
// next-event estimation to the punctual lights and to emissive triangles (area lights, combined
// with BSDF sampling by multiple importance sampling, power heuristic); lights standing in for
// emissive meshes are skipped, so nothing counts twice; the skybox on a miss; Russian roulette
// after a few bounces.
// Materials are Tandem's (Table 1), read as a stochastic mix of lobes:
//   transparency t = 1 - opacity -> Fresnel dielectric (ior against the environment's ior);
//   (1 - t) * reflectivity       -> perfect mirror;
//   the rest                     -> Lambert diffuse kd / pi + normalised Blinn-Phong
//                                   ks (n + 8) / (8 pi) cos^n(theta_h), as shadeBlinnPhong, with
//                                   kd + ks scaled to at most 1 so no energy is created.
// One lobe is chosen per bounce with the probability of its weight, so the weights cancel.
#pragma once
#include <cstdint>

#include "rt/ray_tracer.h"
#include "rt/sampler.h"
#include "shading/blinn_phong.h"

namespace tandem {

// A direction about unit n with density cos(theta) / pi, from two uniform numbers.
Vec3 sampleCosine(Vec3 n, float u1, float u2);

struct PathSettings {
  int maxDepth = 16;      // [1, 1024] bounces
  int rouletteDepth = 3;  // Russian roulette from this bounce on
};

// Emissive triangles as area lights: chosen in proportion to area x emitted luminance, then a
// uniform point on the triangle.
class EmitterTable {
 public:
  explicit EmitterTable(const FrameScene& fs);
  bool empty() const { return total_ <= 0; }
  // Picks a triangle and a point on it (where the triangle is at shutter fraction `time`);
  // `pdfArea` is the density per unit area of that point.
  bool sample(float u, Vec2 uv, float time, int& object, int& prim, Vec3& point,
              float& pdfArea) const;
  // The density per unit area with which sample() picks a point of (object, prim).
  float pdfArea(int object, int prim) const;

 private:
  struct Tri {
    int object, prim;
    float area;
  };
  const FrameScene* frame_;
  std::vector<Tri> tris_;
  std::vector<double> cdf_;
  std::vector<int> objectFirst_;  // first index into tris_ per object, -1 if not emissive
  std::vector<float> weight_;
  double total_ = 0;
};

class PathTracer {
 public:
  PathTracer(const RayTracer& rt, const Scene& scene, const ShadingContext& shading,
             PathSettings settings)
      : rt_(rt), scene_(scene), shading_(shading), settings_(settings), emitters_(*rt.frame()) {}

  // Radiance arriving along the ray (origin, unit dir) back towards its origin, at shutter
  // fraction `time` (motion blur; 0 without).
  Vec3 radiance(Vec3 origin, Vec3 dir, float time, SobolSampler& rng) const;

 private:
  Vec3 directLight(const SurfaceSample& s, Vec3 wo, Vec3 kd, Vec3 ks, float time) const;
  // One area-light sample, MIS-weighted (power heuristic) against BSDF sampling.
  Vec3 areaLight(const SurfaceSample& s, Vec3 wo, Vec3 kd, Vec3 ks, float pd, float time,
                 SobolSampler& rng) const;

  const RayTracer& rt_;
  const Scene& scene_;
  const ShadingContext& shading_;
  PathSettings settings_;
  EmitterTable emitters_;
};

}  // namespace tandem
