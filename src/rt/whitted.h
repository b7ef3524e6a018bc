// Whitted-style secondary effects of Walewski et al. 2019 §3.3 (Listings 8a-8d), shared by the
// hybrid rt_secondary pass (starting from G-buffer samples) and the rt_whitted pass (starting from
// camera rays), so the two produce the same image wherever the same objects are ray traced.
//  - shadow rays to every light, attenuated through transparent occluders (Listing 8b);
//  - reflection and refraction rays (Snell; total internal reflection falls back to reflection);
//  - recursion in hit shading with an importance cutoff and a maximum depth (Listing 8c);
//  - misses return the skybox (Listing 8d);
//  - effects combined by eq. 5-6 (the average of C_M and C_R).
// Hit shading goes through the one Blinn-Phong function.
#pragma once
#include <tbb/combinable.h>

#include <memory>
#include <vector>

#include "raster/shadow_maps.h"
#include "rt/ray_tracer.h"
#include "shading/blinn_phong.h"

namespace tandem {

// How primary surfaces learn each light's visibility: classified (the shadow maps decide where
// they are certain, shadow rays the rest), rays (a shadow ray per light) or maps (2x2 PCF shadow
// maps only, no ray).
enum class ShadowMode { Classified = 0, Rays = 1, Maps = 2 };

// Light-surface pairs by what decided them, summed over a frame's shadow queries.
struct ShadowCounts {
  uint64_t culled = 0, lit = 0, shadowed = 0, traced = 0;
  uint64_t surfaces = 0;  // surfaces asked about (each of them for every light)
  void add(const ShadowCounts& o) {
    culled += o.culled, lit += o.lit, shadowed += o.shadowed, traced += o.traced;
    surfaces += o.surfaces;
  }
  uint64_t pairs() const { return culled + lit + shadowed + traced; }
};
// One ShadowCounts per worker thread (shadow queries run in parallel).
using ShadowTally = tbb::combinable<ShadowCounts>;
ShadowCounts sum(ShadowTally& t);

struct WhittedSettings {
  int maxDepth = 10;               // [1, 64] recursion depth of secondary rays (paper: 10)
  float importanceCutoff = 0.01f;  // [0, 1] stop when the ray's weight falls below this
  // Listing 8b: occluders attenuate by their diffuse colour as the G-buffer would hold it
  // (textures included); false: the material's base diffuse colour.
  bool texturedShadows = true;
  // Listing 8c at the maximum depth: a fully reflective or refractive surface has no lighting
  // (0); true: it is shaded with Blinn-Phong instead.
  bool shadeAtMaxDepth = false;
  ShadowMode shadows = ShadowMode::Rays;  // Classified and Maps need shadow maps (useShadowMaps)
  // Culling: a light whose unshadowed contribution to a surface is below this fraction of the
  // surface's unshadowed total gets no shadow query and counts as visible (0: only lights facing
  // away, outside their cone or range are left out).
  float shadowCull = 0.0f;
};

// Eq. 5-6: C_M = OM M + (1 - OM)(OR R + (1 - OR) C), C_R = OR R + (1 - OR)(OM M + (1 - OM) C),
// result (C_M + C_R) / 2, with OM the reflectivity and OR the transparency (1 - opacity).
Vec3 combineEffects(float reflectivity, float transparency, Vec3 reflection, Vec3 refraction,
                    Vec3 lighting);

Vec3 reflectDir(Vec3 d, Vec3 n);
// A secondary ray's origin: the surface point moved off the surface towards the side `dir`
// leaves to, by an amount scaled to the position's magnitude (large scenes do not self-hit).
Vec3 offsetRayOrigin(const SurfaceSample& s, Vec3 dir);
// The shadow ray from surface s towards a light sample: offset off the surface, stopping just
// short of a punctual light (unbounded for a directional one), at shutter fraction `time`.
Ray shadowRayTowards(const SurfaceSample& s, const LightSample& ls, float time);
// Refracts d at a surface with normal n facing against d, eta = n_incident / n_transmitted.
// Returns false on total internal reflection.
bool refractDir(Vec3 d, Vec3 n, float eta, Vec3& out);

// Per-light RGB visibility of up to 8 lanes, laid out as shadeBatch reads it:
// [(3 * light + channel) * 8 + lane]. On the stack for the usual light counts.
// Not initialised: the rows of the lights decided are written before they are read.
class LightVisibility8 {
 public:
  explicit LightVisibility8(size_t lights) {
    if (lights > 32) heap_ = std::make_unique_for_overwrite<float[]>(3 * 8 * lights);
  }
  float* data() { return heap_ ? heap_.get() : stack_; }

 private:
  float stack_[3 * 8 * 32];
  std::unique_ptr<float[]> heap_;
};

class Whitted {
 public:
  Whitted(const RayTracer& rt, const Scene& scene, const ShadingContext& shading,
          WhittedSettings settings)
      : rt_(rt), scene_(scene), shading_(shading), settings_(settings) {}

  // The same tracer with every ray it makes (shadow, reflection, refraction) at shutter
  // fraction `time`: the motion-blurred surfaces of a sample at that time (reference renders).
  Whitted atTime(float time) const {
    Whitted w = *this;
    w.time_ = time;
    return w;
  }
  // The frame's shadow maps, for ShadowMode Classified and Maps (without them every shadow is
  // traced), and where to count what decided each shadow (optional).
  void useShadowMaps(const ShadowMaps* maps) { maps_ = maps; }
  void countShadows(ShadowTally* tally) { tally_ = tally; }

  // Per-light RGB transmittance from the surface point to each light (1 where a light casts no
  // shadows or does not face the point). `vis` has one entry per scene light.
  void lightVisibility(const SurfaceSample& s, Vec3* vis) const;
  // The same for up to 8 surfaces, each light's shadow rays in one 8-wide Embree packet, into a
  // LightVisibility8 (lanes >= n are 1), decided as the settings' shadow mode says. wo (unit,
  // surface -> viewer; optional): lets the culling weigh each light's share of the surface's
  // light. rays (optional, 8 entries): shadow rays per lane. classes (optional): each light's
  // ShadowClass per lane at [8 * light + lane]. reached (optional): only the lights that may
  // reach some lane (lightsReaching) are decided, listed there ascending, and only their rows of
  // vis written (every other light adds exactly 0: shade with b.lights = reached); without it
  // every light's row is written.
  void lightVisibility8(const SurfaceSample* s, int n, float* vis, int* rays = nullptr,
                        const Vec3* wo = nullptr, uint8_t* classes = nullptr,
                        std::vector<uint32_t>* reached = nullptr) const;
  // The reflection and refraction colours seen from a primary surface hit by direction d
  // (zero where the surface is not reflective / not transparent).
  Vec3 primaryReflection(const SurfaceSample& s, Vec3 d) const;
  Vec3 primaryRefraction(const SurfaceSample& s, Vec3 d) const;
  // A secondary ray (Listing 8c/8d): depth starts at 1 for rays leaving a primary surface.
  Vec3 traceSecondary(Vec3 origin, Vec3 dir, int depth, float importance) const;
  // Full ray-traced shading of a primary surface: shadows, reflection, refraction, combined.
  Vec3 shadePrimary(const SurfaceSample& s, Vec3 d) const;
  // The same for up to 8 surfaces (a 4x2 pixel block): each light's shadow rays in one 8-wide
  // Embree packet, the lighting in one shading batch; out[i] = shadePrimary(s[i], d[i]).
  void shadePrimary8(const SurfaceSample* s, const Vec3* d, int n, Vec3* out) const;

 private:
  Vec3 reflectionFrom(const SurfaceSample& s, Vec3 d, int depth, float importance) const;
  Vec3 refractionFrom(const SurfaceSample& s, Vec3 d, int depth, float importance) const;
  // The shadow ray towards light `light` of `s`; false where none is needed (the light casts no
  // shadows, does not face the point, or is dark).
  bool shadowRay(const SurfaceSample& s, size_t light, Ray& r) const;

  const RayTracer& rt_;
  const Scene& scene_;
  const ShadingContext& shading_;
  WhittedSettings settings_;
  float time_ = 0.0f;  // shutter fraction of every ray this tracer makes
  const ShadowMaps* maps_ = nullptr;
  ShadowTally* tally_ = nullptr;
};

}  // namespace tandem
