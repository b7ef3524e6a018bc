// Peres 2022's diffuse global illumination on the GPU (rt/diffuse_gi.cpp, operation for
// operation): a light picked by the LightGrid (or uniformly) with its shadow ray, one
// cosine-weighted bounce with its own; and the brightest lights' direct light. Shared by
// reference.comp (diffuse-gi), foveated_pt.comp and direct_light.comp. The including kernel
// includes scene.glsl and whitted.glsl (rays, offsetRayOrigin) first and sets `giGrid`.
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer GiFloats { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer GiInts { int v[]; };

GpuLightGrid giGrid;

vec3 toWorld(vec3 l, vec3 n) {  // orthonormalBasis (core/math.h)
  const float sgn = n.z >= 0.0 ? 1.0 : -1.0;
  const float q = -1.0 / (sgn + n.z), bb = n.x * n.y * q;
  const vec3 t = vec3(1.0 + sgn * n.x * n.x * q, sgn * bb, -sgn * n.x);
  const vec3 b = vec3(bb, sgn + n.y * n.y * q, -n.y);
  return t * l.x + b * l.y + n * l.z;
}
vec3 sampleCosine(vec3 n, float u1, float u2) {
  const float r = sqrt(u1), phi = 2.0 * kPi * u2;
  return toWorld(vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u1))), n);
}

// LightGrid::pick at p with u: the light (-1: none) and its probability.
int gridPick(vec3 p, float u, out float pdf) {
  pdf = 0.0;
  const int n = giGrid.count;
  GiInts candidates = GiInts(giGrid.candidates);
  if (n == 0) return -1;
  pdf = 1.0;
  if (n == 1) return candidates.v[0];
  u = clamp(u, 0.0, uintBitsToFloat(0x3f7fffffu));
  const vec3 f = (p - v3(giGrid.lo)) * v3(giGrid.invCell);
  int cell = 0, stride = 1;
  for (int k = 0; k < 3; ++k) {
    const int c = clamp(int(floor(clamp(f[k], -1.0, 1e6))), 0, giGrid.dims[k] - 1);
    cell += c * stride;
    stride *= giGrid.dims[k];
  }
  GiFloats cdf = GiFloats(giGrid.cdf);
  const uint base = uint(cell) * uint(n);
  if (cdf.v[base + uint(n - 1)] <= 0.0) {
    const int i = min(int(u * float(n)), n - 1);
    pdf = 1.0 / float(n);
    return candidates.v[i];
  }
  // std::upper_bound: the first entry greater than u.
  int lo = 0, hi = n;
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (cdf.v[base + uint(mid)] <= u)
      lo = mid + 1;
    else
      hi = mid;
  }
  const int i = min(lo, n - 1);
  pdf = cdf.v[base + uint(i)] - (i > 0 ? cdf.v[base + uint(i - 1)] : 0.0);
  return candidates.v[i];
}

vec3 giAlbedo(Surface s) { return clamp(s.diffuse, vec3(0.0), vec3(1.0)); }
vec3 giEmitted(Surface s, vec3 wo) { return dot(s.geoNormal, wo) > 0.0 ? s.emission : vec3(0.0); }

// Whether light i's shadow ray from s towards wi (dist away) is blocked.
bool giOccluded(Surface s, GpuLight l, vec3 wi, float dist) {
  if (l.castsShadows == 0u) return false;
  ++rays;
  TraceHit h;
  const float tfar = isinf(dist) ? kInf : dist * (1.0 - 1e-4);
  return traverse(offsetRayOrigin(s, wi), wi, 0.0, tfar, TRACE_ANY | TRACE_FILTERED, h);
}

// DiffuseGI::oneLight: irradiance / pi from one light the grid picks, over its probability.
vec3 giOneLight(Surface s, vec3 n, float u) {
  float pdf;
  const int i = gridPick(s.position, u, pdf);
  if (i < 0 || !(pdf > 0.0)) return vec3(0.0);
  const GpuLight l = Lights(S.lights).l[i];
  vec3 wi, radiance;
  float dist;
  sampleLight(l, s.position, wi, dist, radiance);
  const float cosI = dot(n, wi);
  if (cosI <= 0.0 || maxComponent(radiance) <= 0.0) return vec3(0.0);
  if (giOccluded(s, l, wi, dist)) return vec3(0.0);
  return radiance * (cosI / (pdf * kPi));
}

// DiffuseGI::reflected: the light picked at s and one cosine-weighted bounce (its emission and
// its own picked light), with u0, u1, u2 the sampler's next three pairs.
vec3 giReflected(Surface s, vec3 wo, vec2 u0, vec2 u1, vec2 u2) {
  const vec3 n = dot(s.normal, wo) < 0.0 ? -s.normal : s.normal;
  vec3 sum = giOneLight(s, n, u0.x);
  // Cosine-weighted bounce: Lambert's cos / pi cancels the density.
  const vec3 dir = safeNormalize(sampleCosine(n, u1.x, u1.y));
  if (dot(dir, s.geoNormal) * dot(n, s.geoNormal) <= 0.0) return sum;  // below the surface
  const vec3 origin = offsetRayOrigin(s, dir);
  ++rays;
  TraceHit g;
  if (!traverse(origin, dir, 0.0, 1e30, TRACE_FILTERED, g)) return sum + skyRadiance(dir);
  const Surface hs = resolveSurface(g.object, g.prim, origin, dir, g.t, g.u, g.v, 0.0);
  const vec3 wh = -dir;
  const vec3 nh = dot(hs.normal, wh) < 0.0 ? -hs.normal : hs.normal;
  return sum + giEmitted(hs, wh) + giAlbedo(hs) * giOneLight(hs, nh, u2.x);
}

// DiffuseGI::radiance.
vec3 giRadiance(Surface s, vec3 wo, vec2 u0, vec2 u1, vec2 u2) {
  return giEmitted(s, wo) + giAlbedo(s) * giReflected(s, wo, u0, u1, u2);
}

// DiffuseGI::brightestDirect: of the grid's candidates, the `count` giving s the most unshadowed
// light (luminance x cosine, ties by index), brightest first, each with its shadow ray.
vec3 giBrightestDirect(Surface s, vec3 wo, int count) {
  const vec3 n = dot(s.normal, wo) < 0.0 ? -s.normal : s.normal;
  GiInts candidates = GiInts(giGrid.candidates);
  vec3 sum = vec3(0.0);
  float lastKey = kInf;
  int lastLight = -1;
  for (int c = 0; c < count; ++c) {
    // The next candidate in the CPU's sorted order: after (lastKey, lastLight).
    int best = -1;
    float bestKey = 0.0, bestDist = 0.0;
    vec3 bestWi = vec3(0.0), bestRadiance = vec3(0.0);
    for (int k = 0; k < giGrid.count; ++k) {
      const int i = candidates.v[k];
      vec3 wi, radiance;
      float dist;
      sampleLight(Lights(S.lights).l[i], s.position, wi, dist, radiance);
      const float cosI = dot(n, wi);
      if (cosI <= 0.0 || maxComponent(radiance) <= 0.0) continue;
      precise const float key = luminance(radiance) * cosI;
      if (!(key < lastKey || (key == lastKey && i > lastLight))) continue;
      if (best >= 0 && !(key > bestKey || (key == bestKey && i < best))) continue;
      best = i, bestKey = key, bestDist = dist, bestWi = wi, bestRadiance = radiance;
    }
    if (best < 0) break;
    lastKey = bestKey;
    lastLight = best;
    if (giOccluded(s, Lights(S.lights).l[best], bestWi, bestDist)) continue;
    sum += bestRadiance * (dot(n, bestWi) / kPi);
  }
  return sum;
}
