// Raster shadow maps on the GPU: ShadowMaps::classify (classified shadows: lit, shadowed or left
// to a ray) and ShadowMaps::visibility (2x2 percentage-closer lookups) operation for operation,
// reading the maps shadow_maps_data.h lays out. The including kernel includes
// shadow_maps_data.h and scene.glsl, and calls useShadowMaps before asking.

#define TD_SHADOW_CULLED 0
#define TD_SHADOW_LIT 1
#define TD_SHADOW_SHADOWED 2
#define TD_SHADOW_TRACED 3

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ShadowHeaderRef {
  GpuShadowMapsHeader h;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer ShadowLightsRef {
  GpuShadowLight l[];
};
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ShadowFacesRef {
  GpuShadowFace f[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer ShadowTexelsRef {
  float v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ShadowKeysRef {
  uvec2 v[];  // a uint64 key's (low, high) words: (the complement of an index, depth bits)
};

GpuShadowMapsHeader shadowMaps;

void useShadowMaps(uint64_t address) { shadowMaps = ShadowHeaderRef(address).h; }

int cubeFaceOf(vec3 d) {  // core/math.h cubeFace
  const float ax = abs(d.x), ay = abs(d.y), az = abs(d.z);
  return ax >= ay && ax >= az ? (d.x > 0.0 ? 0 : 1) : ay >= az ? (d.y > 0.0 ? 2 : 3)
                                                               : (d.z > 0.0 ? 4 : 5);
}

// The face of light i that sees p (-1: the light has no maps).
int shadowFaceFor(uint i, vec3 p) {
  if (i >= shadowMaps.lightCount) return -1;
  const GpuShadowLight l = ShadowLightsRef(shadowMaps.lights).l[i];
  if (l.faceCount == 0) return -1;
  if (l.faceCount != 6) return l.firstFace;
  const GpuShadowFace f0 = ShadowFacesRef(shadowMaps.faces).f[l.firstFace];
  return l.firstFace + cubeFaceOf(p - v3(f0.eye));
}

float faceRow(GpuShadowFace f, int r, vec3 q) {
  return f.viewProj[4 * r] * q.x + f.viewProj[4 * r + 1] * q.y + f.viewProj[4 * r + 2] * q.z +
         f.viewProj[4 * r + 3];
}

// A caster of reversed-Z depth d lies more than a gap nearer the light than p when d * a > b.
struct ShadowLimit {
  float a, b;
};
bool limitMet(ShadowLimit l, float d) { return d * l.a > l.b; }
// The limit of casters more than `gap` nearer the light than a point `along` the face's axis.
ShadowLimit shadowLimit(GpuShadowFace f, float along, float gap) {
  const float z = along - gap;
  if (f.perspective != 0) return z > f.nearPlane ? ShadowLimit(z, f.nearPlane) : ShadowLimit(0.0, 1.0);
  return ShadowLimit(f.farPlane - f.nearPlane, f.farPlane - z);
}

// ShadowMaps::classify of light i at p (geometric normal n) on object `self`: TD_SHADOW_LIT,
// _SHADOWED or _TRACED.
int shadowClassify(uint i, vec3 p, vec3 n, int self) {
  const int fi = shadowFaceFor(i, p);
  if (fi < 0) {
    const bool casts =
        i < shadowMaps.lightCount && ShadowLightsRef(shadowMaps.lights).l[i].casts != 0;
    return casts ? TD_SHADOW_TRACED : TD_SHADOW_LIT;
  }
  const GpuShadowFace f = ShadowFacesRef(shadowMaps.faces).f[fi];
  const bool perspective = f.perspective != 0;
  const vec3 rel = p - v3(f.eye), forward = v3(f.forward);
  const float along = dot(rel, forward);
  if (perspective && along <= f.nearPlane) return TD_SHADOW_TRACED;
  const float nr = perspective ? dot(n, rel) : dot(n, forward);
  const float r2 = perspective ? dot(rel, rel) : 1.0;
  if (nr * nr < 0.01 * r2) return TD_SHADOW_TRACED;  // grazing
  const float texel = perspective ? along * f.texelPerDistance : f.texelPerDistance;
  const float tangent = sqrt(max(r2 - nr * nr, 0.0)) / abs(nr);
  const float slope = texel * (1.4143 * tangent + 1.0);
  const float w = perspective ? faceRow(f, 3, p) : 1.0;
  if (perspective && w <= 1e-8) return TD_SHADOW_TRACED;
  const float iw = 1.0 / w;
  const float sx = (faceRow(f, 0, p) * iw * 0.5 + 0.5) * float(f.width);
  const float sy = (0.5 - faceRow(f, 1, p) * iw * 0.5) * float(f.height);
  if (!(sx >= 1.0 && sy >= 1.0 && sx < float(f.width - 1) && sy < float(f.height - 1)))
    return TD_SHADOW_TRACED;
  const ShadowLimit own = shadowLimit(f, along, slope);
  // Another object counts from the shadow ray's own start offset on (offsetRayOrigin).
  const ShadowLimit other = shadowLimit(f, along, 1e-4 * (1.0 + maxComponent(max(p, -p))));
  const ShadowLimit shadow = shadowLimit(f, along, slope + 2.0 * texel);
  // Lit: no caster touching the texels the shadow ray projects onto is nearer than p, beyond the
  // receiver's own slope.
  const float e = 0.02;
  const int tx0 = int(sx - e), tx1 = int(sx + e), ty0 = int(sy - e), ty1 = int(sy + e);
  ShadowKeysRef near = ShadowKeysRef(f.near);
  bool blocked = false;
  for (int y = ty0; y <= ty1; ++y)
    for (int x = tx0; x <= tx1; ++x) {
      const uvec2 t = near.v[uint(y) * uint(f.width) + uint(x)];
      blocked = blocked || limitMet(int(~t.x) == self ? own : other, uintBitsToFloat(t.y));
    }
  if (!blocked) return TD_SHADOW_LIT;
  // Shadowed: every texel centre around p holds an opaque static caster well in front of it.
  const int cx = int(sx), cy = int(sy);
  ShadowTexelsRef opaque = ShadowTexelsRef(f.opaque);
  for (int y = cy - 1; y <= cy + 1; ++y)
    for (int x = cx - 1; x <= cx + 1; ++x)
      if (!limitMet(shadow, opaque.v[uint(y) * uint(f.width) + uint(x)])) return TD_SHADOW_TRACED;
  return TD_SHADOW_SHADOWED;
}

// ShadowMaps::visibility: the fraction of light i reaching p (unit normal n), 1 where light i
// has no maps or p lies outside them.
float shadowVisibility(uint i, vec3 p, vec3 n) {
  const int fi = shadowFaceFor(i, p);
  if (fi < 0) return 1.0;
  const GpuShadowFace f = ShadowFacesRef(shadowMaps.faces).f[fi];
  const bool perspective = f.perspective != 0;
  const vec3 eye = v3(f.eye), forward = v3(f.forward);
  const float along = dot(p - eye, forward);
  if (perspective && along <= f.nearPlane) return 1.0;
  // Offset along the normal against acne, scaled with the map's texel footprint.
  const float texel = perspective ? along * f.texelPerDistance : f.texelPerDistance;
  const vec3 q = p + n * (1.5 * texel);
  const float w = faceRow(f, 3, q);
  if (perspective && w <= 1e-8) return 1.0;
  const float iw = 1.0 / w;
  const float sx = (faceRow(f, 0, q) * iw * 0.5 + 0.5) * float(f.width);
  const float sy = (0.5 - faceRow(f, 1, q) * iw * 0.5) * float(f.height);
  const float fx = floor(sx - 0.5), fy = floor(sy - 0.5);
  if (!(fx >= -1.0 && fy >= -1.0 && fx < float(f.width) && fy < float(f.height))) return 1.0;
  const int cx = int(fx), cy = int(fy);
  const float dq = dot(q - eye, forward);
  const float bias = 2.0 * texel;
  // A tap is lit when its surface lies no nearer than dq - bias along the axis.
  float threshold;
  if (perspective)
    threshold = dq - bias > 0.0 ? f.nearPlane / (dq - bias) : kInf;
  else
    threshold = (f.farPlane + bias - dq) / (f.farPlane - f.nearPlane);
  const int x0 = clamp(cx, 0, f.width - 1), x1 = clamp(cx + 1, 0, f.width - 1);
  const int y0 = clamp(cy, 0, f.height - 1), y1 = clamp(cy + 1, 0, f.height - 1);
  ShadowKeysRef depth = ShadowKeysRef(f.depth);
  const uint w0 = uint(f.width);
  int lit = 0;
  const float taps[4] = float[](uintBitsToFloat(depth.v[uint(y0) * w0 + uint(x0)].y),
                                uintBitsToFloat(depth.v[uint(y0) * w0 + uint(x1)].y),
                                uintBitsToFloat(depth.v[uint(y1) * w0 + uint(x0)].y),
                                uintBitsToFloat(depth.v[uint(y1) * w0 + uint(x1)].y));
  for (int k = 0; k < 4; ++k) lit += taps[k] <= 0.0 || taps[k] <= threshold ? 1 : 0;
  return float(lit) * 0.25;
}
