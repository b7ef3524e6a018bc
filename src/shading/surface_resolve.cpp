#include "shading/surface_resolve.h"

#include "shading/surface_resolve_inline.h"

#include <cmath>

namespace tandem {

bool intersectTriangle(Vec3 o, Vec3 d, Vec3 a, Vec3 b, Vec3 c, float& t, float& u, float& v) {
  // Möller-Trumbore, evaluated relative to vertex a for precision.
  Vec3 e1 = b - a, e2 = c - a;
  Vec3 p = cross(d, e2);
  float det = dot(e1, p);
  if (det == 0.0f) {
    t = u = v = 0;
    return false;
  }
  float inv = 1.0f / det;
  Vec3 s = o - a;
  u = dot(s, p) * inv;
  Vec3 q = cross(s, e1);
  v = dot(d, q) * inv;
  t = dot(e2, q) * inv;
  return true;
}

float surfaceAlpha(const FrameScene& fs, int object, int prim, float u, float v) {
  const Scene& scene = *fs.scene;
  const Object& obj = scene.objects[object];
  const Material& mat = scene.materials[obj.material];
  const Mesh& mesh = scene.meshes[obj.mesh];
  float alpha = mat.diffuseOpacity;
  if (mat.diffuseTexture < 0) return alpha;
  const uint32_t* idx = &mesh.indices[3 * size_t(prim)];
  float w = 1.0f - u - v;
  Vec2 uv = mesh.uvs[idx[0]] * w + mesh.uvs[idx[1]] * u + mesh.uvs[idx[2]] * v;
  return alpha * scene.textures[mat.diffuseTexture].sample(mat.transformUv(uv)).w;
}

SurfaceSample resolveSurface(const FrameScene& fs, int object, int prim, Vec3 origin, Vec3 dir,
                             float time) {
  return resolveSurface(fs, object, prim, origin, dir, time, nullptr);
}

TriangleSetup TriangleSetup::make(const FrameScene& fs, int object, int prim, float time) {
  const Scene& scene = *fs.scene;
  const Object& obj = scene.objects[size_t(object)];
  TriangleSetup t;
  t.fs = &fs;
  t.object = object;
  t.prim = prim;
  t.materialIndex = obj.material;
  t.mat = &scene.materials[size_t(obj.material)];
  t.fo = &fs.objects[size_t(object)];
  t.mesh = &scene.meshes[obj.mesh];
  t.idx = &t.mesh->indices[3 * size_t(prim)];
  const bool moving = !t.fo->stepPositions.empty();  // motion blur: the triangle at the ray's time
  for (int k = 0; k < 3; ++k) {
    t.p[k] = moving ? positionAt(*t.fo, t.idx[k], time) : t.fo->positions[t.idx[k]];
    t.n[k] = moving ? normalAt(*t.fo, t.idx[k], time) : t.fo->normals[t.idx[k]];
  }
  t.worldCross = cross(t.p[1] - t.p[0], t.p[2] - t.p[0]);  // twice the area, along the normal
  t.geoNormal = normalize(t.worldCross);
  t.hasUvs = !t.mesh->uvs.empty();
  if (t.hasUvs)
    for (int k = 0; k < 3; ++k) t.uv[k] = t.mesh->uvs[t.idx[k]];
  if (t.mat->hasTexture() && t.hasUvs) {
    const Vec2 e1 = t.uv[1] - t.uv[0], e2 = t.uv[2] - t.uv[0];
    const float uvArea = std::abs(e1.x * e2.y - e1.y * e2.x);
    t.worldArea = length(t.worldCross);
    if (t.worldArea > 0.0f) t.uvPerWorld = std::sqrt(uvArea / t.worldArea);
  }
  return t;
}

SurfaceSample resolveSurface(const FrameScene& fs, int object, int prim, Vec3 origin, Vec3 dir,
                             float time, const float* knownTuv, float pixelSpread) {
  return resolveSurface(TriangleSetup::make(fs, object, prim, time), origin, dir, knownTuv,
                        pixelSpread);
}

SurfaceSample resolveSurface(const TriangleSetup& tri, Vec3 origin, Vec3 dir, const float* knownTuv,
                             float pixelSpread) {
  return resolveSurfaceInline(tri, origin, dir, knownTuv, pixelSpread);
}

float pixelSpreadAngle(const Camera& camera) {
  if (camera.desc.projection != Projection::Perspective) return 0.0f;
  return 2.0f * camera.tanHalfFov / float(std::max(camera.height, 1));
}

}  // namespace tandem
