// Resolves a triangle hit (object, primitive, ray) into a SurfaceSample: barycentrics from the
// ray, interpolated normals/tangents/UVs, material and textures. The raster G-buffer (via its
// visibility buffer) and every ray hit go through this one function.
#pragma once
#include <cstdint>
#include <vector>

#include "scene/frame_scene.h"
#include "shading/surface.h"

namespace tandem {

// Barycentrics (u, v) and distance t of the ray against triangle (a, b, c), without culling.
// Returns false only when the ray is parallel to the triangle's plane.
bool intersectTriangle(Vec3 o, Vec3 d, Vec3 a, Vec3 b, Vec3 c, float& t, float& u, float& v);

SurfaceSample resolveSurface(const FrameScene& fs, int object, int prim, Vec3 origin, Vec3 dir,
                             float time = 0.0f);
// The same, given the ray tracer's distance and barycentrics `knownTuv` = {t, u, v} (u: vertex 1,
// v: vertex 2) instead of intersecting the triangle again; null: intersect from origin and dir.
// `pixelSpread`: the angle (radians) one pixel subtends at the eye, for primary hits: the pixel's
// cone (Akenine-Moller et al. 2019, ray cones) is `pixelSpread x distance` wide at the hit, and
// textures are filtered trilinearly at the level that width covers on this triangle (its UV to
// world area ratio, widened by 1 / cos of the incidence). Raster pixels and primary rays use
// the same estimate, so their G-buffers agree; 0 samples full resolution (secondary rays).
SurfaceSample resolveSurface(const FrameScene& fs, int object, int prim, Vec3 origin, Vec3 dir,
                             float time, const float* knownTuv, float pixelSpread = 0.0f);

// The per-triangle part of resolveSurface: the object's material and mesh, the vertices (at the
// ray's time), their normals and UVs, the geometric normal and the UV-to-world scale. A pass
// resolving many pixels of one triangle sets it up once (the result is bit for bit the same).
struct TriangleSetup {
  const FrameScene* fs = nullptr;
  int object = -1, prim = -1, materialIndex = -1;
  const Material* mat = nullptr;
  const Mesh* mesh = nullptr;
  const FrameObject* fo = nullptr;
  const uint32_t* idx = nullptr;
  Vec3 p[3], n[3];
  Vec2 uv[3]{};  // zero when the mesh has none
  bool hasUvs = false;
  Vec3 worldCross, geoNormal;
  float worldArea = 0, uvPerWorld = 0;  // set for textured materials with UVs

  static TriangleSetup make(const FrameScene& fs, int object, int prim, float time);
};
SurfaceSample resolveSurface(const TriangleSetup& tri, Vec3 origin, Vec3 dir, const float* knownTuv,
                             float pixelSpread = 0.0f);

// Triangles set up recently by one worker (direct-mapped, 64 entries): neighbouring pixels
// mostly hit the same triangles. `Extra` is what a caller keeps beside each set-up (the raster
// resolve: its barycentric planes). For objects standing still during the frame (the set-up is
// at time 0); valid for one frame.
template <class Extra = char>
struct TriangleSetupCache {
  struct Entry {
    uint32_t object = ~0u, prim = ~0u;
    TriangleSetup setup;
    Extra extra{};
  };
  static constexpr size_t kSize = 64;
  std::vector<Entry> entries = std::vector<Entry>(kSize);

  // The entry of (object, prim), set up if it was not there; `fresh` tells the caller to fill
  // its extra.
  Entry& get(const FrameScene& fs, uint32_t object, uint32_t prim, bool& fresh) {
    Entry& e = entries[(prim * 0x9E3779B1u + object) % kSize];
    fresh = e.object != object || e.prim != prim;
    if (fresh) {
      e.object = object;
      e.prim = prim;
      e.setup = TriangleSetup::make(fs, int(object), int(prim), 0.0f);
    }
    return e;
  }
};

// The pixel spread angle of a camera (0 for orthographic: no level of detail).
float pixelSpreadAngle(const Camera& camera);

// Alpha of the material's diffuse texture at the hit (alpha-mask tests).
float surfaceAlpha(const FrameScene& fs, int object, int prim, float u, float v);

}  // namespace tandem
