#include "shading/surface_resolve.h"

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

SurfaceSample resolveSurface(const FrameScene& fs, int object, int prim, Vec3 origin, Vec3 dir,
                             float time, const float* knownTuv, float pixelSpread) {
  const Scene& scene = *fs.scene;
  const Object& obj = scene.objects[object];
  const FrameObject& fo = fs.objects[object];
  const Mesh& mesh = scene.meshes[obj.mesh];
  const Material& mat = scene.materials[obj.material];
  const uint32_t* idx = &mesh.indices[3 * size_t(prim)];
  const bool moving = !fo.stepPositions.empty();  // motion blur: the triangle at the ray's time
  const Vec3 a = moving ? positionAt(fo, idx[0], time) : fo.positions[idx[0]];
  const Vec3 b = moving ? positionAt(fo, idx[1], time) : fo.positions[idx[1]];
  const Vec3 c = moving ? positionAt(fo, idx[2], time) : fo.positions[idx[2]];
  float t, u, v;
  if (knownTuv)  // the ray tracer's own hit: its barycentrics, no second intersection
    t = knownTuv[0], u = knownTuv[1], v = knownTuv[2];
  else
    intersectTriangle(origin, dir, a, b, c, t, u, v);
  // Pixels on an edge can land a hair outside [0,1]; clamp so attributes stay convex.
  u = std::clamp(u, 0.0f, 1.0f);
  v = std::clamp(v, 0.0f, 1.0f - u);
  const float w = 1.0f - u - v;

  SurfaceSample s;
  s.object = object;
  s.material = obj.material;
  s.t = t;
  s.position = a * w + b * u + c * v;
  const Vec3 worldCross = cross(b - a, c - a);  // twice the triangle's area, along its normal
  s.geoNormal = normalize(worldCross);
  auto normal = [&](uint32_t i) { return moving ? normalAt(fo, i, time) : fo.normals[i]; };
  Vec3 n = normalize(normal(idx[0]) * w + normal(idx[1]) * u + normal(idx[2]) * v);
  if (mat.doubleSided && dot(s.geoNormal, dir) > 0) {
    s.geoNormal = -s.geoNormal;
    n = -n;
  }
  Vec2 uvMesh = mesh.uvs[idx[0]] * w + mesh.uvs[idx[1]] * u + mesh.uvs[idx[2]] * v;
  s.uv = mat.transformUv(uvMesh);
  // Each texture at the level of detail of the pixel's cone: its width at the hit, across the
  // surface (1 / cos), in UV units through the triangle's UV / world scale (and the tiling).
  float footprint = 0.0f;
  if (pixelSpread > 0.0f && mat.hasTexture() && !mesh.uvs.empty()) {
    const Vec2 e1 = mesh.uvs[idx[1]] - mesh.uvs[idx[0]], e2 = mesh.uvs[idx[2]] - mesh.uvs[idx[0]];
    const float uvArea = std::abs(e1.x * e2.y - e1.y * e2.x), worldArea = length(worldCross);
    const float dirLength = length(dir);
    if (worldArea > 0.0f && dirLength > 0.0f) {
      const float cosine = std::abs(dot(s.geoNormal, dir)) / dirLength;
      const float width = pixelSpread * length(s.position - origin) / std::max(cosine, 0.05f);
      footprint = width * std::sqrt(uvArea / worldArea) *
                  std::max(std::abs(mat.tiling.x), std::abs(mat.tiling.y));
    }
  }
  auto sampleTex = [&](int i) {
    const Texture& t = scene.textures[size_t(i)];
    return t.sample(s.uv, t.lodFor(footprint));
  };

  s.diffuse = mat.diffuse;
  s.diffuseOpacity = mat.diffuseOpacity;
  if (mat.diffuseTexture >= 0) {
    Vec4 tex = sampleTex(mat.diffuseTexture);
    s.diffuse = s.diffuse * tex.xyz();
    s.diffuseOpacity *= tex.w;
  }
  s.ambient = mat.ambient;
  s.emission = mat.emission;
  if (mat.emissionTexture >= 0) s.emission = s.emission * sampleTex(mat.emissionTexture).xyz();
  s.specular = mat.specular;
  if (mat.specularTexture >= 0) s.specular = s.specular * sampleTex(mat.specularTexture).xyz();
  s.specularExponent = mat.specularExponent;
  s.reflectivity = mat.reflectivity;
  if (mat.metallicRoughnessTexture >= 0) {
    Vec4 mr = sampleTex(mat.metallicRoughnessTexture);
    Vec3 base = mat.baseColor;
    if (mat.diffuseTexture >= 0) base = base * sampleTex(mat.diffuseTexture).xyz();
    BlinnPhongTerms bp = fromMetallicRoughness(base, mat.metallic * mr.z, mat.roughness * mr.y);
    s.diffuse = bp.diffuse;
    s.ambient = bp.diffuse;
    s.specular = bp.specular;
    s.specularExponent = bp.exponent;
    s.reflectivity = bp.reflectivity;
  }
  s.ior = mat.ior;
  s.opacity = mat.opacity;
  if (mat.alphaMode == AlphaMode::Blend) s.opacity = std::min(s.opacity, s.diffuseOpacity);

  if (mat.normalTexture >= 0) {
    Vec4 tg = fo.tangents[idx[0]] * w + fo.tangents[idx[1]] * u + fo.tangents[idx[2]] * v;
    Vec3 tangent = normalize(tg.xyz() - n * dot(n, tg.xyz()));
    Vec3 bitangent = cross(n, tangent) * (fo.tangents[idx[0]].w < 0 ? -1.0f : 1.0f);
    Vec4 tex = sampleTex(mat.normalTexture);
    Vec3 tn{(tex.x * 2 - 1) * mat.normalScale, (tex.y * 2 - 1) * mat.normalScale, tex.z * 2 - 1};
    Vec3 mapped = normalize(tangent * tn.x + bitangent * tn.y + n * tn.z);
    if (isFinite(mapped) && length(mapped) > 0.5f) n = mapped;
  }
  s.normal = n;
  return s;
}

float pixelSpreadAngle(const Camera& camera) {
  if (camera.desc.projection != Projection::Perspective) return 0.0f;
  return 2.0f * camera.tanHalfFov / float(std::max(camera.height, 1));
}

}  // namespace tandem
