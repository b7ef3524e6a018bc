// The body of resolveSurface(const TriangleSetup&, ...), inline for the raster resolve's pixel
// loop: there the sample goes straight from registers into the G-buffer (through memory, a
// freshly written sample stalls the loads that read it back). Everything else calls the
// out-of-line resolveSurface, which is this function.
#pragma once
#include <algorithm>
#include <cmath>

#include "scene/scene.h"
#include "shading/blinn_phong.h"
#include "shading/surface_resolve.h"

namespace tandem {

[[gnu::always_inline]] inline SurfaceSample resolveSurfaceInline(const TriangleSetup& tri,
                                                                 Vec3 origin, Vec3 dir,
                                                                 const float* knownTuv,
                                                                 float pixelSpread) {
  const Scene& scene = *tri.fs->scene;
  const FrameObject& fo = *tri.fo;
  const Material& mat = *tri.mat;
  const uint32_t* idx = tri.idx;
  const Vec3 a = tri.p[0], b = tri.p[1], c = tri.p[2];
  float t, u, v;
  if (knownTuv)  // the ray tracer's own hit: its barycentrics, no second intersection
    t = knownTuv[0], u = knownTuv[1], v = knownTuv[2];
  else
    intersectTriangle(origin, dir, a, b, c, t, u, v);
  // Pixels on an edge can land a hair outside [0,1]; clamp so attributes stay convex.
  u = std::clamp(u, 0.0f, 1.0f);
  v = std::clamp(v, 0.0f, 1.0f - u);
  const float w = 1.0f - u - v;

  // Every field is computed into a local and the sample built once at the end: a default-built
  // sample is zero-filled first (a `rep stos` per pixel) and then overwritten.
  const Vec3 position = a * w + b * u + c * v;
  Vec3 geoNormal = tri.geoNormal;
  Vec3 n = normalize(tri.n[0] * w + tri.n[1] * u + tri.n[2] * v);
  if (mat.doubleSided && dot(geoNormal, dir) > 0) {
    geoNormal = -geoNormal;
    n = -n;
  }
  Vec2 uvMesh = tri.uv[0] * w + tri.uv[1] * u + tri.uv[2] * v;
  const Vec2 uv = mat.transformUv(uvMesh);
  // Each texture at the level of detail of the pixel's cone: its width at the hit, across the
  // surface (1 / cos), in UV units through the triangle's UV / world scale (and the tiling).
  // width = spread x distance / max(cos, 0.05) with distance = t |d| (a known hit's t) and
  // cos = |g . d| / |d|: one square root and one division.
  float footprint = 0.0f;
  if (pixelSpread > 0.0f && mat.hasTexture() && tri.hasUvs) {
    const float dd = dot(dir, dir);
    if (tri.worldArea > 0.0f && dd > 0.0f) {
      const float dirLength = std::sqrt(dd);
      const float along = knownTuv && t > 0.0f ? t * dd : length(position - origin) * dirLength;
      const float width =
          pixelSpread * along / std::max(std::abs(dot(geoNormal, dir)), 0.05f * dirLength);
      footprint = width * tri.uvPerWorld * std::max(std::abs(mat.tiling.x), std::abs(mat.tiling.y));
    }
  }
  auto sampleTex = [&](int i) {
    const Texture& t = scene.textures[size_t(i)];
    return t.sample(uv, t.lodFor(footprint));
  };

  Vec3 diffuse = mat.diffuse;
  float diffuseOpacity = mat.diffuseOpacity;
  if (mat.diffuseTexture >= 0) {
    Vec4 tex = sampleTex(mat.diffuseTexture);
    diffuse = diffuse * tex.xyz();
    diffuseOpacity *= tex.w;
  }
  Vec3 ambient = mat.ambient;
  Vec3 emission = mat.emission;
  if (mat.emissionTexture >= 0) emission = emission * sampleTex(mat.emissionTexture).xyz();
  Vec3 specular = mat.specular;
  if (mat.specularTexture >= 0) specular = specular * sampleTex(mat.specularTexture).xyz();
  float specularExponent = mat.specularExponent;
  float reflectivity = mat.reflectivity;
  if (mat.metallicRoughnessTexture >= 0) {
    Vec4 mr = sampleTex(mat.metallicRoughnessTexture);
    Vec3 base = mat.baseColor;
    if (mat.diffuseTexture >= 0) base = base * sampleTex(mat.diffuseTexture).xyz();
    BlinnPhongTerms bp = fromMetallicRoughness(base, mat.metallic * mr.z, mat.roughness * mr.y);
    diffuse = bp.diffuse;
    ambient = bp.diffuse;
    specular = bp.specular;
    specularExponent = bp.exponent;
    reflectivity = bp.reflectivity;
  }
  if (mat.occlusionTexture >= 0)  // after the metallic-roughness terms, which reset ambient
    ambient = ambient * (1.0f + mat.occlusionStrength * (sampleTex(mat.occlusionTexture).x - 1.0f));
  float opacity = mat.opacity;
  if (mat.alphaMode == AlphaMode::Blend) opacity = std::min(opacity, diffuseOpacity);

  if (mat.normalTexture >= 0) {
    Vec4 tg = fo.tangents[idx[0]] * w + fo.tangents[idx[1]] * u + fo.tangents[idx[2]] * v;
    Vec3 tangent = normalize(tg.xyz() - n * dot(n, tg.xyz()));
    Vec3 bitangent = cross(n, tangent) * (fo.tangents[idx[0]].w < 0 ? -1.0f : 1.0f);
    Vec4 tex = sampleTex(mat.normalTexture);
    Vec3 tn{(tex.x * 2 - 1) * mat.normalScale, (tex.y * 2 - 1) * mat.normalScale, tex.z * 2 - 1};
    Vec3 mapped = normalize(tangent * tn.x + bitangent * tn.y + n * tn.z);
    if (isFinite(mapped) && length(mapped) > 0.5f) n = mapped;
  }
  return SurfaceSample{
      position,          n,        geoNormal,        uv,           emission, ambient, diffuse,
      diffuseOpacity,    specular, specularExponent, reflectivity, mat.ior,  opacity, tri.object,
      tri.materialIndex, t};
}

}  // namespace tandem
