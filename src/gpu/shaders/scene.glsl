// The scene's surfaces on the GPU, operation for operation what the CPU computes: texture
// sampling (scene/texture.cpp), resolveSurface (shading/surface_resolve_inline.h), the one
// Blinn-Phong shading function (shading/shade_batch.cpp), the sky (Scene::skyRadiance) and the
// hit filters of RayTracer (alpha masks, back-face culling for camera rays, Listing 8b's shadow
// attenuation). The including kernel sets `S` (and `bvh` from it: useScene) before using any.

#include "traverse.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer SceneRef {
  SceneArgs s;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Materials {
  GpuMaterial m[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Textures {
  GpuTexture t[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Levels {
  GpuTextureLevel l[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Lights {
  GpuLight l[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Objects {
  GpuObject o[];
};

SceneArgs S;

void useScene(uint64_t address) {
  S = SceneRef(address).s;
  bvh = BvhRefs(S.nodes, S.triangles, S.trianglePrim, S.objectRoot, S.topRoot, S.objectMotion,
                S.motionTriangles);
}

const float kPi = 3.14159265358979323846;
float kInf = uintBitsToFloat(0x7f800000u);  // (no constant expression makes an infinity)

vec3 v3(float a[3]) { return vec3(a[0], a[1], a[2]); }
float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }
#include "color.glsl"
vec3 safeNormalize(vec3 v) {  // as math.h normalize: zero stays zero
  const float l2 = dot(v, v);
  return l2 > 0.0 ? v / sqrt(l2) : vec3(0.0);
}

// --- Textures ---------------------------------------------------------------------------------

int positiveMod(int i, int n) { return i >= 0 ? i % n : n - 1 - ((-i - 1) % n); }
int wrapIndex(int i, int n, uint mode) {
  if (mode == 1u) return clamp(i, 0, n - 1);  // clamp to edge
  if (mode == 2u) {                           // mirrored repeat
    const int m = positiveMod(i, 2 * n);
    return m < n ? m : 2 * n - 1 - m;
  }
  return positiveMod(i, n);
}

float decodeTexel(uint texel, int channel, bool srgb) {
  const uint byte = (texel >> (8u * uint(channel))) & 255u;
  return Floats(S.decode).v[(srgb && channel < 3 ? 0u : 256u) + byte];
}

vec4 bilinear(GpuTextureLevel l, vec2 uv, uint ws, uint wt, bool srgb) {
  const int w = l.width, h = l.height;
  const float fx = clamp(uv.x * float(w) - 0.5, -1e7, 1e7);
  const float fy = clamp(uv.y * float(h) - 0.5, -1e7, 1e7);
  const float x0f = floor(fx), y0f = floor(fy);
  const float tx = fx - x0f, ty = fy - y0f;
  const int x0 = int(x0f), y0 = int(y0f);
  const int xa = wrapIndex(x0, w, ws), xb = wrapIndex(x0 + 1, w, ws);
  const int ya = wrapIndex(y0, h, wt), yb = wrapIndex(y0 + 1, h, wt);
  Uints texels = Uints(S.texels);
  const uint p00 = texels.v[l.offset + uint(ya * w + xa)];
  const uint p10 = texels.v[l.offset + uint(ya * w + xb)];
  const uint p01 = texels.v[l.offset + uint(yb * w + xa)];
  const uint p11 = texels.v[l.offset + uint(yb * w + xb)];
  vec4 out4;
  for (int k = 0; k < 4; ++k) {
    const float top = decodeTexel(p00, k, srgb) * (1.0 - tx) + decodeTexel(p10, k, srgb) * tx;
    const float bottom = decodeTexel(p01, k, srgb) * (1.0 - tx) + decodeTexel(p11, k, srgb) * tx;
    out4[k] = top * (1.0 - ty) + bottom * ty;
  }
  return out4;
}

// Texture::sample(uv, lod): trilinear between the two levels around lod.
vec4 sampleTexture(int index, vec2 uv, float lod) {
  const GpuTexture t = Textures(S.textures).t[index];
  if (t.levels == 0u) return vec4(1.0);
  if (any(isnan(uv)) || any(isinf(uv))) uv = vec2(0.0);
  Levels levels = Levels(S.levels);
  const bool srgb = t.srgb != 0u;
  const float top = float(t.levels - 1u);
  if (!(lod > 0.0)) return bilinear(levels.l[t.firstLevel], uv, t.wrapS, t.wrapT, srgb);
  lod = min(lod, top);
  const int l0 = int(lod);
  const float f = lod - float(l0);
  const vec4 a = bilinear(levels.l[t.firstLevel + uint(l0)], uv, t.wrapS, t.wrapT, srgb);
  if (f <= 0.0 || l0 + 1 > int(top)) return a;
  return a * (1.0 - f) +
         bilinear(levels.l[t.firstLevel + uint(l0) + 1u], uv, t.wrapS, t.wrapT, srgb) * f;
}

float lodFor(int index, float uvPerPixel) {
  const GpuTexture t = Textures(S.textures).t[index];
  if (t.levels == 0u || !(uvPerPixel > 0.0)) return 0.0;
  const float texels = uvPerPixel * float(t.size);
  return texels > 1.0 ? log2(texels) : 0.0;
}

// --- Surfaces ---------------------------------------------------------------------------------

struct Surface {  // SurfaceSample
  vec3 position, normal, geoNormal;
  vec2 uv;
  vec3 emission, ambient, diffuse;
  float diffuseOpacity;
  vec3 specular;
  float specularExponent, reflectivity, ior, opacity;
  int object, material;
  float t;
};

vec3 vertexPosition(uint v) {
  Floats p = Floats(S.positions);
  return vec3(p.v[3u * v], p.v[3u * v + 1u], p.v[3u * v + 2u]);
}
vec3 vertexNormal(uint v) {
  Floats p = Floats(S.normals);
  return vec3(p.v[3u * v], p.v[3u * v + 1u], p.v[3u * v + 2u]);
}
vec4 vertexTangent(uint v) {
  Floats p = Floats(S.tangents);
  return vec4(p.v[4u * v], p.v[4u * v + 1u], p.v[4u * v + 2u], p.v[4u * v + 3u]);
}
vec2 vertexUv(uint v) {
  Floats p = Floats(S.uvs);
  return vec2(p.v[2u * v], p.v[2u * v + 1u]);
}
// Vertex v (an index into the shared arrays) of object `ob` where it is at traceTau: a moving
// object's between its time steps (positionAt, normalAt), any other's as the frame has it.
vec3 vertexPositionAt(GpuObject ob, uint v) {
  if (ob.motionSteps < 2u) return vertexPosition(v);
  float frac;
  const uint at = ob.firstStep + (v - ob.firstVertex) * ob.motionSteps + stepAt(ob.motionSteps, frac);
  Floats p = Floats(S.stepPositions);
  return lerp3(floats3(p, 3u * at), floats3(p, 3u * at + 3u), frac);
}
vec3 vertexNormalAt(GpuObject ob, uint v) {
  if (ob.motionSteps < 2u) return vertexNormal(v);
  float frac;
  const uint at = ob.firstStep + (v - ob.firstVertex) * ob.motionSteps + stepAt(ob.motionSteps, frac);
  Floats n = Floats(S.stepNormals);
  return safeNormalize(lerp3(floats3(n, 3u * at), floats3(n, 3u * at + 3u), frac));
}
uvec3 triangleVertices(GpuObject ob, int prim) {
  Uints idx = Uints(S.indices);
  const uint i = ob.firstIndex + 3u * uint(prim);
  return uvec3(idx.v[i], idx.v[i + 1u], idx.v[i + 2u]) + uvec3(ob.firstVertex);
}

// The object whose triangles include `triangle` (an index over all objects' triangles): the last
// one starting at or before it.
int objectOfTriangle(uint triangle, uint objectCount) {
  int lo = 0, hi = int(objectCount) - 1;
  while (lo < hi) {
    const int mid = (lo + hi + 1) / 2;
    if (Objects(S.objects).o[mid].firstIndex / 3u <= triangle)
      lo = mid;
    else
      hi = mid - 1;
  }
  return lo;
}

bool hasTexture(GpuMaterial m) {
  return m.diffuseTexture >= 0 || m.emissionTexture >= 0 || m.specularTexture >= 0 ||
         m.metallicRoughnessTexture >= 0 || m.normalTexture >= 0 || m.occlusionTexture >= 0;
}
// Material::transformUv: offset + R(rotation) (uv x tiling).
vec2 transformUv(GpuMaterial m, vec2 uv) {
  vec2 s = uv * vec2(m.tiling[0], m.tiling[1]);
  if ((m.flags & TD_MAT_UV_ROTATION) != 0u)
    s = vec2(m.uvCos * s.x + m.uvSin * s.y, -m.uvSin * s.x + m.uvCos * s.y);
  return s + vec2(m.offset[0], m.offset[1]);
}

// intersectTriangle (shading/surface_resolve.cpp): Moller-Trumbore relative to vertex a, no
// bounds on t, u, v; false only for a ray parallel to the plane.
bool intersectTriangle(vec3 o, vec3 d, vec3 a, vec3 b, vec3 c, out float t, out float u,
                       out float v) {
  const vec3 e1 = b - a, e2 = c - a;
  const vec3 p = cross(d, e2);
  const float det = dot(e1, p);
  t = u = v = 0.0;
  if (det == 0.0) return false;
  const float inv = 1.0 / det;
  const vec3 s = o - a;
  u = dot(s, p) * inv;
  const vec3 q = cross(s, e1);
  v = dot(d, q) * inv;
  t = dot(e2, q) * inv;
  return true;
}

// Alpha of the material's diffuse texture at barycentrics (u, v) (surfaceAlpha).
float surfaceAlpha(int object, int prim, float u, float v) {
  const GpuObject ob = Objects(S.objects).o[object];
  const GpuMaterial m = Materials(S.materials).m[ob.material];
  if (m.diffuseTexture < 0) return m.diffuseOpacity;
  const uvec3 k = triangleVertices(ob, prim);
  const float w = 1.0 - u - v;
  vec2 uv = vec2(0.0);
  if (ob.hasUvs != 0u) uv = vertexUv(k.x) * w + vertexUv(k.y) * u + vertexUv(k.z) * v;
  return m.diffuseOpacity * sampleTexture(m.diffuseTexture, transformUv(m, uv), 0.0).w;
}

// fromMetallicRoughness (scene/material.cpp).
void metallicRoughness(vec3 base, float metal, float rough, out vec3 diffuse, out vec3 specular,
                       out float exponent, out float reflectivity) {
  metal = clamp(metal, 0.0, 1.0);
  rough = clamp(rough, 0.0, 1.0);
  const float alpha = max(rough * rough, 1e-3);
  diffuse = base * (1.0 - metal);
  specular = mix(vec3(0.04), base, metal);
  exponent = clamp(2.0 / (alpha * alpha) - 2.0, 1.0, 4096.0);
  reflectivity = metal * (1.0 - rough);
}

// resolveSurface: the hit (t, u, v) of the ray (origin, dir) on triangle `prim` of `object`;
// `pixelSpread` > 0 filters textures at the pixel cone's footprint (primary hits).
Surface resolveSurface(int object, int prim, vec3 origin, vec3 dir, float t, float u, float v,
                       float pixelSpread) {
  const GpuObject ob = Objects(S.objects).o[object];
  const GpuMaterial m = Materials(S.materials).m[ob.material];
  const uvec3 k = triangleVertices(ob, prim);
  const vec3 a = vertexPositionAt(ob, k.x), b = vertexPositionAt(ob, k.y),
             c = vertexPositionAt(ob, k.z);
  const vec3 worldCross = cross(b - a, c - a);
  vec3 geoNormal = safeNormalize(worldCross);
  const bool textured = hasTexture(m) && ob.hasUvs != 0u;
  float worldArea = 0.0, uvPerWorld = 0.0;
  vec2 uv0 = vec2(0.0), uv1 = vec2(0.0), uv2 = vec2(0.0);
  if (ob.hasUvs != 0u) uv0 = vertexUv(k.x), uv1 = vertexUv(k.y), uv2 = vertexUv(k.z);
  if (textured) {
    const vec2 e1 = uv1 - uv0, e2 = uv2 - uv0;
    const float uvArea = abs(e1.x * e2.y - e1.y * e2.x);
    worldArea = length(worldCross);
    if (worldArea > 0.0) uvPerWorld = sqrt(uvArea / worldArea);
  }
  // Pixels on an edge can land a hair outside [0,1]; clamp so attributes stay convex.
  u = clamp(u, 0.0, 1.0);
  v = clamp(v, 0.0, 1.0 - u);
  const float w = 1.0 - u - v;
  const vec3 position = a * w + b * u + c * v;
  vec3 n = safeNormalize(vertexNormalAt(ob, k.x) * w + vertexNormalAt(ob, k.y) * u +
                         vertexNormalAt(ob, k.z) * v);
  if ((m.flags & TD_MAT_DOUBLE_SIDED) != 0u && dot(geoNormal, dir) > 0.0) {
    geoNormal = -geoNormal;
    n = -n;
  }
  const vec2 uv = transformUv(m, uv0 * w + uv1 * u + uv2 * v);
  float footprint = 0.0;
  if (pixelSpread > 0.0 && textured) {
    const float dd = dot(dir, dir);
    if (worldArea > 0.0 && dd > 0.0) {
      const float dirLength = sqrt(dd);
      const float along = t > 0.0 ? t * dd : length(position - origin) * dirLength;
      const float width = pixelSpread * along / max(abs(dot(geoNormal, dir)), 0.05 * dirLength);
      footprint = width * uvPerWorld * max(abs(m.tiling[0]), abs(m.tiling[1]));
    }
  }
  Surface s;
  s.diffuse = v3(m.diffuse);
  s.diffuseOpacity = m.diffuseOpacity;
  if (m.diffuseTexture >= 0) {
    const vec4 tex = sampleTexture(m.diffuseTexture, uv, lodFor(m.diffuseTexture, footprint));
    s.diffuse *= tex.xyz;
    s.diffuseOpacity *= tex.w;
  }
  s.ambient = v3(m.ambient);
  s.emission = v3(m.emission);
  if (m.emissionTexture >= 0)
    s.emission *= sampleTexture(m.emissionTexture, uv, lodFor(m.emissionTexture, footprint)).xyz;
  s.specular = v3(m.specular);
  if (m.specularTexture >= 0)
    s.specular *= sampleTexture(m.specularTexture, uv, lodFor(m.specularTexture, footprint)).xyz;
  s.specularExponent = m.specularExponent;
  s.reflectivity = m.reflectivity;
  if (m.metallicRoughnessTexture >= 0) {
    const int mr = m.metallicRoughnessTexture;
    const vec4 tex = sampleTexture(mr, uv, lodFor(mr, footprint));
    vec3 base = v3(m.baseColor);
    if (m.diffuseTexture >= 0)
      base *= sampleTexture(m.diffuseTexture, uv, lodFor(m.diffuseTexture, footprint)).xyz;
    metallicRoughness(base, m.metallic * tex.z, m.roughness * tex.y, s.diffuse, s.specular,
                      s.specularExponent, s.reflectivity);
    s.ambient = s.diffuse;
  }
  if (m.occlusionTexture >= 0) {
    const float occ =
        sampleTexture(m.occlusionTexture, uv, lodFor(m.occlusionTexture, footprint)).x;
    s.ambient *= 1.0 + m.occlusionStrength * (occ - 1.0);
  }
  s.opacity = m.opacity;
  if ((m.flags & TD_MAT_ALPHA_BLEND) != 0u) s.opacity = min(s.opacity, s.diffuseOpacity);
  if (m.normalTexture >= 0 && ob.hasTangents != 0u) {
    const vec4 t0 = vertexTangent(k.x);
    const vec4 tg = t0 * w + vertexTangent(k.y) * u + vertexTangent(k.z) * v;
    const vec3 tangent = safeNormalize(tg.xyz - n * dot(n, tg.xyz));
    const vec3 bitangent = cross(n, tangent) * (t0.w < 0.0 ? -1.0 : 1.0);
    const vec4 tex = sampleTexture(m.normalTexture, uv, lodFor(m.normalTexture, footprint));
    const vec3 tn = vec3((tex.x * 2.0 - 1.0) * m.normalScale, (tex.y * 2.0 - 1.0) * m.normalScale,
                         tex.z * 2.0 - 1.0);
    const vec3 mapped = safeNormalize(tangent * tn.x + bitangent * tn.y + n * tn.z);
    if (!any(isnan(mapped)) && !any(isinf(mapped)) && length(mapped) > 0.5) n = mapped;
  }
  s.position = position;
  s.normal = n;
  s.geoNormal = geoNormal;
  s.uv = uv;
  s.ior = m.ior;
  s.object = object;
  s.material = int(ob.material);
  s.t = t;
  return s;
}

// --- Lights and shading -----------------------------------------------------------------------

// sampleLight: the unit direction towards light l from p, its distance (infinite for a
// directional light) and its radiance there (no visibility).
void sampleLight(GpuLight l, vec3 p, out vec3 wi, out float dist, out vec3 radiance) {
  if (l.type == 0u) {
    wi = -v3(l.direction);
    dist = kInf;
    radiance = v3(l.power);
    return;
  }
  const vec3 d = v3(l.position) - p;
  dist = sqrt(dot(d, d));
  wi = dist > 0.0 ? d / dist : vec3(0.0, 1.0, 0.0);
  radiance = vec3(0.0);
  if (l.range > 0.0 && dist > l.range) return;
  float att = 1.0 / max(l.attConstant + l.attLinear * dist + l.attQuadratic * dist * dist, 1e-8);
  if (l.type == 2u) {
    const float cosTheta = dot(-wi, v3(l.direction));
    float cone;
    if (l.hemisphere != 0u) {
      cone = cosTheta > 0.0 ? 1.0 : 0.0;
    } else if (l.cosInner <= l.cosOuter) {
      cone = cosTheta >= l.cosOuter ? 1.0 : 0.0;
    } else {
      const float x = clamp((cosTheta - l.cosOuter) / (l.cosInner - l.cosOuter), 0.0, 1.0);
      cone = x * x * (3.0 - 2.0 * x);
    }
    if (l.cosinePower > 0.0) cone *= pow(max(cosTheta, 0.0), l.cosinePower);
    att *= cone;
  }
  radiance = v3(l.power) * att;
}

// What light l reflects from s towards wo, unshadowed (one light's term of shadeBatch).
vec3 lightTerm(Surface s, vec3 wo, GpuLight l) {
  vec3 wi, radiance;
  float dist;
  sampleLight(l, s.position, wi, dist, radiance);
  const float nDotL = dot(s.normal, wi);
  if (!(nDotL > 0.0)) return vec3(0.0);
  const vec3 kd = s.diffuse * (1.0 / kPi);
  const vec3 ks = s.specular * ((s.specularExponent + 8.0) * (1.0 / (8.0 * kPi)));
  float lobe = 0.0;
  if (ks.x + ks.y + ks.z != 0.0) {
    const vec3 h = wi + wo;
    const float nDotH = max(dot(s.normal, h) * inversesqrt(max(dot(h, h), 1e-30)), 0.0);
    lobe = exp(s.specularExponent * log(max(nDotH, 1e-30)));
  }
  return (ks * lobe + kd) * (radiance * nDotL);
}

// Emission and the global ambient term.
vec3 selfTerm(Surface s) { return v3(S.ambient) * s.ambient + s.emission; }

// shadeBlinnPhong without shadows (secondary hits).
vec3 shadeUnshadowed(Surface s, vec3 wo) {
  vec3 c = selfTerm(s);
  Lights lights = Lights(S.lights);
  for (uint i = 0u; i < S.lightCount; ++i) c += lightTerm(s, wo, lights.l[i]);
  return c;
}

// --- The sky ----------------------------------------------------------------------------------

vec3 skyRadiance(vec3 d) {
  if (S.skyFaces[0] < 0) return v3(S.skyColor);
  const float ax = abs(d.x), ay = abs(d.y), az = abs(d.z);
  int face;
  float sc, tc, ma;
  if (ax >= ay && ax >= az) {
    face = d.x > 0.0 ? 0 : 1;
    ma = ax;
    sc = d.x > 0.0 ? -d.z : d.z;
    tc = -d.y;
  } else if (ay >= az) {
    face = d.y > 0.0 ? 2 : 3;
    ma = ay;
    sc = d.x;
    tc = d.y > 0.0 ? d.z : -d.z;
  } else {
    face = d.z > 0.0 ? 4 : 5;
    ma = az;
    sc = d.z > 0.0 ? d.x : -d.x;
    tc = -d.y;
  }
  if (!(ma > 0.0)) return v3(S.skyColor);
  return sampleTexture(S.skyFaces[face], vec2(0.5 * (sc / ma + 1.0), 0.5 * (tc / ma + 1.0)), 0.0)
      .xyz;
}

// --- Hit filters (RayTracer's callbacks) --------------------------------------------------------

const uint TRACE_CULL_BACK = 8u;  // camera rays: back faces of single-sided materials missed
const uint TRACE_SHADOW = 16u;    // Listing 8b: hits attenuate `shadowT`
const uint TRACE_TEXTURED = 32u;  // ... by the occluder's textured colour (else its base colour)

vec3 shadowT;
// The surfaces a shadow ray has counted (a ray through a shared edge meets both triangles at
// the same distance and must attenuate once): a ring of the 8 most recent.
int countedObject[8];
float countedT[8];
int countedN;

int hitFilter(uint flags, int object, int prim, float t, float u, float v, vec3 ng, vec3 o,
              vec3 d) {
  const GpuObject ob = Objects(S.objects).o[object];
  const GpuMaterial m = Materials(S.materials).m[ob.material];
  if ((m.flags & TD_MAT_ALPHA_MASK) != 0u && surfaceAlpha(object, prim, u, v) < m.alphaCutoff)
    return HIT_IGNORE;
  if ((flags & TRACE_CULL_BACK) != 0u && (m.flags & TD_MAT_DOUBLE_SIDED) == 0u && dot(ng, d) >= 0.0)
    return HIT_IGNORE;
  if ((flags & TRACE_SHADOW) == 0u) return HIT_ACCEPT;
  if ((m.flags & TD_MAT_CASTS_SHADOWS) == 0u) return HIT_IGNORE;
  for (int k = 0; k < min(countedN, 8); ++k)
    if (countedObject[k] == object && abs(countedT[k] - t) <= 1e-5 * max(1.0, t)) return HIT_IGNORE;
  countedObject[countedN % 8] = object;
  countedT[countedN % 8] = t;
  ++countedN;
  vec3 diffuse = v3(m.diffuse);
  float opacity = m.opacity;
  if ((flags & TRACE_TEXTURED) != 0u && m.opacity < 1.0) {
    const Surface s = resolveSurface(object, prim, o, d, t, u, v, 0.0);
    diffuse = s.diffuse;
    opacity = s.opacity;
  }
  shadowT *= (vec3(1.0) - min(diffuse, vec3(1.0))) * (1.0 - opacity) * v3(m.transmissionFilter);
  return maxComponent(shadowT) > 0.0 ? HIT_IGNORE : HIT_STOP;
}

// RayTracer::transmittance: what passes from o along d up to tfar (Listing 8b).
vec3 transmittance(vec3 o, vec3 d, float tfar, bool textured) {
  shadowT = vec3(1.0);
  countedN = 0;
  TraceHit h;
  const uint flags = TRACE_ALL | TRACE_FILTERED | TRACE_SHADOW | (textured ? TRACE_TEXTURED : 0u);
  if (traverse(o, d, 0.0, tfar, flags, h)) return vec3(0.0);
  return shadowT;
}
