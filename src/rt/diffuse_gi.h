// The foveated path tracer's light transport (Peres 2022 §4.3, Wyman et al. 2018's diffuse global
// illumination): at the primary surface one shadow ray to a light chosen at random (next-event
// estimation; uniformly as in the thesis, or by a LightGrid's estimate of each light's irradiance
// there), one cosine-weighted indirect ray, and at the indirect hit its emission
// plus one more random-light shadow ray; an indirect miss sees the sky. The BRDF is Lambert's
// (diffuse albedo / π) everywhere: specular lobes, mirrors and glass are not part of this
// transport. Lights standing in for emissive meshes are skipped (their mesh's emission is seen
// by the indirect ray instead). The foveated_pt pass and the reference's diffuse-gi integrator
// both call it, so the reference is the same path tracer, only converged.
#pragma once
#include <string>
#include <vector>

#include "rt/light_grid.h"
#include "rt/ray_tracer.h"
#include "rt/sampler.h"
#include "shading/blinn_phong.h"

namespace tandem {

class DiffuseGI {
 public:
  // `grid`, when given, picks the lights (built over lightsSampled(scene)); otherwise uniform.
  DiffuseGI(const RayTracer& rt, const Scene& scene, const ShadingContext& shading,
            const LightGrid* grid = nullptr);

  // The lights the estimator samples: the scene's, less the stand-ins for emissive meshes.
  static std::vector<int> lightsSampled(const Scene& scene);
  // A selection grid over the scene's bounds for these lights; with `rt`, its visibility probed.
  static LightGrid buildGrid(const Scene& scene, const ShadingContext& shading,
                             const RayTracer* rt = nullptr);

  // One path's estimate of the light the primary surface `s` reflects towards wo (unit, surface
  // -> viewer), divided by its diffuse albedo: the outgoing radiance is s.emission (front side)
  // + albedo x reflected(). Uses three sample pairs of `rng` at shutter fraction `time`; adds the
  // rays it traced to `rays`.
  Vec3 reflected(const SurfaceSample& s, Vec3 wo, SobolSampler& rng, float time,
                 uint64_t& rays) const;
  // The direct light of the `count` lights that give s the most unshadowed light, each with its
  // shadow ray, in reflected()'s units (irradiance / π; no albedo): what reflected()'s next-event
  // estimate averages to for those lights, without its light-selection noise. The rest of the
  // light (other lights, the bounce) is left to the paths.
  Vec3 brightestDirect(const SurfaceSample& s, Vec3 wo, int count, float time,
                       uint64_t& rays) const;
  // The same for up to 8 surfaces (n <= 8), their shadow rays traced as packets, the brightest
  // light of each surface first: out[j] = brightestDirect(s[j], wo[j], ...).
  void brightestDirect8(const SurfaceSample* s, const Vec3* wo, int n, int count, float time,
                        Vec3* out, uint64_t& rays) const;
  // The whole outgoing radiance: emission + albedo x reflected().
  Vec3 radiance(const SurfaceSample& s, Vec3 wo, SobolSampler& rng, float time,
                uint64_t& rays) const;
  // Materials on the scene's objects this transport draws black: metals and other surfaces with
  // a specular colour but no diffuse one (glTF metallic 1). Users are told, not surprised.
  static std::vector<std::string> blackMaterials(const Scene& scene);
  // One line saying which materials draw black, or "" when none does.
  static std::string blackMaterialsNote(const Scene& scene);
  // Lambert's albedo as the transport uses it (the diffuse colour, clamped to [0, 1]).
  static Vec3 albedo(const SurfaceSample& s);
  // Emission seen from wo: emitters light their front side only, as in the path tracer.
  static Vec3 emitted(const SurfaceSample& s, Vec3 wo);

 private:
  // Irradiance / π at s from one light chosen at random (its visibility tested), over the
  // light's selection probability.
  Vec3 oneLight(const SurfaceSample& s, Vec3 n, float u, float time, uint64_t& rays) const;
  // brightestDirect's lights at s: each light's unshadowed contribution, the `count` largest
  // first (ties to the lower index), in `out`; returns how many there are (<= count).
  struct DirectCandidate {
    float luminance;
    int light;
    LightSample sample;
  };
  size_t brightestLights(const SurfaceSample& s, Vec3 n, int count,
                         std::vector<DirectCandidate>& out) const;
  // Light i into `out` (the best `k` so far, in that order) when it lights s at all.
  void considerLight(const SurfaceSample& s, Vec3 n, int i, size_t k,
                     std::vector<DirectCandidate>& out) const;

  const RayTracer& rt_;
  const Scene& scene_;
  const ShadingContext& shading_;
  const LightGrid* grid_;
  std::vector<int> lights_;  // lights the estimator samples (not emissive-mesh stand-ins)
};

}  // namespace tandem
