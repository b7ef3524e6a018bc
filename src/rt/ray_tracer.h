// One Embree 3 scene built from the FrameScene's world-space meshes (geometry id = object id,
// primitive id = triangle index), rebuilt when the geometry version changes. Closest-hit and
// occlusion queries, single rays and 8-wide packets for coherent batches. Alpha-masked and
// single-sided materials get a filter callback: masks discard transparent texels, and camera
// queries may ask for back faces of single-sided surfaces to be culled, as the rasterizer does.
#pragma once
#include <embree3/rtcore.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "scene/frame_scene.h"

namespace tandem {

struct Ray {
  Vec3 origin, dir;
  float tnear = 0.0f, tfar = 1e30f;
  float time = 0.0f;  // shutter fraction in [0,1] (motion blur); 0 = the frame's time
};

struct Hit {
  int object = -1, prim = -1;
  float t = 0, u = 0, v = 0;
  bool valid() const { return object >= 0; }
};

struct GeometryInfo;

class RayTracer {
 public:
  RayTracer();
  ~RayTracer();
  RayTracer(const RayTracer&) = delete;
  RayTracer& operator=(const RayTracer&) = delete;

  // Builds (or rebuilds) the BVH when the frame's geometry changed; returns true if it built.
  bool update(const FrameScene& fs);

  Hit intersect(const Ray& r, bool cullBackfaces = false) const;
  bool occluded(const Ray& r) const;
  // Up to 8 occlusion rays in one coherent Embree packet: out[i] = occluded(rays[i]) for the
  // lanes with active[i] (others untouched).
  void occluded8(const Ray* rays, const bool* active, bool* out) const;
  // Shadow ray (Walewski et al. 2019 Listing 8b): the product over occluders of transparency x (1 -
  // diffuse), skipping materials that do not cast shadows; 0 once an opaque occluder is met.
  // `textured`: the occluder's diffuse colour at the hit, textures included (what the G-buffer
  // would hold); otherwise the material's base diffuse colour.
  Vec3 transmittance(const Ray& r, bool textured = true) const;
  // Up to 8 shadow rays in one coherent Embree packet: out[i] = transmittance(rays[i]) for the
  // lanes with active[i] (others untouched). Each lane attenuates on its own (Listing 8b).
  void transmittance8(const Ray* rays, const bool* active, Vec3* out, bool textured = true) const;
  // Up to 8 rays in one Embree packet; `count` active lanes.
  void intersect8(const Ray* rays, int count, Hit* hits, bool cullBackfaces = false) const;

  const FrameScene* frame() const { return frame_; }
  uint64_t raysTraced() const;
  // Rays traced so far by the calling worker thread (differences give one pixel's rays).
  uint64_t raysOnThisThread() const;
  void resetRayCount();

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  const FrameScene* frame_ = nullptr;
  uint64_t builtVersion_ = ~0ull;
  std::vector<std::unique_ptr<GeometryInfo>> geometryInfo_;
  // Rays traced, one counter per worker thread: a single shared atomic cost ~18 % of the RT passes
  // in cache-line contention on two cores.
  struct alignas(64) RayCounter {
    std::atomic<uint64_t> n{0};
  };
  void countRays(uint64_t n) const;
  std::unique_ptr<RayCounter[]> rays_;
  size_t rayCounters_ = 0;
};

}  // namespace tandem
