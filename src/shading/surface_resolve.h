// Resolves a triangle hit (object, primitive, ray) into a SurfaceSample: barycentrics from the
// ray, interpolated normals/tangents/UVs, material and textures. The raster G-buffer (via its
// visibility buffer) and every ray hit go through this one function.
#pragma once
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
SurfaceSample resolveSurface(const FrameScene& fs, int object, int prim, Vec3 origin, Vec3 dir,
                             float time, const float* knownTuv);

// Alpha of the material's diffuse texture at the hit (alpha-mask tests).
float surfaceAlpha(const FrameScene& fs, int object, int prim, float u, float v);

}  // namespace tandem
