// Whitted recursion on the GPU (rt/whitted.cpp), shared by rt_whitted.comp and
// rt_secondary.comp: the reflection and refraction directions, and Whitted::traceSecondary as an
// explicit depth-first stack of weighted rays (eq. 5-6 are linear in the reflected, refracted and
// local colours, so each ray carries the weight its colour has in the pixel and adds its own
// lighting there). The including kernel sets `whitted` before tracing.

struct WhittedConfig {
  int maxDepth;
  float importanceCutoff, shadowCull;
  uint flags;  // TD_WHITTED_*
};
WhittedConfig whitted;
uint rays = 0u;                   // rays this invocation traced
uint culled = 0u, traced = 0u;    // shadow queries shadePrimary left out and traced
uint shadowLit = 0u, shadowShadowed = 0u;  // ... and the shadow maps decided

// Eq. 5-6 as weights: C = wm M + wr R + wc C_local.
void effectWeights(float om, float orr, out float wm, out float wr, out float wc) {
  wm = 0.5 * om * (2.0 - orr);
  wr = 0.5 * orr * (2.0 - om);
  wc = (1.0 - om) * (1.0 - orr);
}

// offsetRayOrigin: off the surface towards the side `dir` leaves to.
vec3 offsetRayOrigin(Surface s, vec3 dir) {
  const float eps = 1e-4 * (1.0 + maxComponent(max(s.position, -s.position)));
  return s.position + s.geoNormal * (dot(dir, s.geoNormal) > 0.0 ? eps : -eps);
}

vec3 reflectDir(vec3 d, vec3 n) { return d - n * (2.0 * dot(d, n)); }

// The reflection and refraction directions leaving s for a ray along d (Whitted::reflectionFrom,
// refractionFrom: total internal reflection falls back to the mirror direction).
vec3 reflectionDir(Surface s, vec3 d) {
  const vec3 n = dot(s.normal, d) > 0.0 ? -s.normal : s.normal;
  return safeNormalize(reflectDir(d, n));
}
vec3 refractionDir(Surface s, vec3 d) {
  const bool entering = dot(s.geoNormal, d) < 0.0;
  const vec3 n = dot(s.normal, d) > 0.0 ? -s.normal : s.normal;
  const float eta = entering ? S.environmentIor / s.ior : s.ior / S.environmentIor;
  const float cosi = -dot(d, n);
  const float k = 1.0 - eta * eta * (1.0 - cosi * cosi);
  if (k < 0.0) return safeNormalize(reflectDir(d, n));
  return safeNormalize(d * eta + n * (eta * cosi - sqrt(k)));
}

// Lighting of a primary surface with its shadows (Whitted::shadePrimary8's shading): a light
// below shadow_cull of the surface's unshadowed light is not asked about; one that is, by a
// shadow ray, or (a kernel that includes shadow_maps.glsl, with TD_WHITTED_CLASSIFIED or _MAPS)
// by the frame's shadow maps first.
vec3 shadePrimary(Surface s, vec3 wo) {
  Lights lights = Lights(S.lights);
  const vec3 self = selfTerm(s);
#ifdef TD_SHADOW_TRACED
  const bool classified = (whitted.flags & TD_WHITTED_CLASSIFIED) != 0u;
  const bool mapsOnly = (whitted.flags & TD_WHITTED_MAPS) != 0u;
#else
  const bool classified = false, mapsOnly = false;
#endif
  // Shares decide what is asked with a cull floor, and always with the maps (Whitted's `shares`).
  const bool shares = whitted.shadowCull > 0.0 || classified || mapsOnly;
  float floorShare = 0.0;
  if (shares) {
    vec3 total = self;
    for (uint i = 0u; i < S.lightCount; ++i) total += lightTerm(s, wo, lights.l[i]);
    floorShare = whitted.shadowCull * luminance(total);
  }
  vec3 c = self;
  for (uint i = 0u; i < S.lightCount; ++i) {
    const GpuLight l = lights.l[i];
    const vec3 term = lightTerm(s, wo, l);
    const float share = luminance(term);
    const bool asked = shares ? l.castsShadows != 0u && share > 0.0 && share >= floorShare
                              : l.castsShadows != 0u;
    // 0 culled, 1 lit, 2 shadowed, 3 traced (ShadowClass)
    int cls = asked ? 3 : 0;
    vec3 vis = vec3(1.0);
#ifdef TD_SHADOW_TRACED
    if (asked && classified) cls = shadowClassify(i, s.position, s.geoNormal, s.object);
    if (asked && mapsOnly) {
      const float v = shadowVisibility(i, s.position, s.geoNormal);
      vis = vec3(v);
      cls = v > 0.5 ? 1 : 2;
    }
#endif
    if (cls == 2 && !mapsOnly) vis = vec3(0.0);
    vec3 wi, radiance;
    float dist;
    sampleLight(l, s.position, wi, dist, radiance);
    if (cls == 3 && !(dot(s.normal, wi) > 0.0 && maxComponent(radiance) > 0.0)) cls = 0;
    if (cls == 3) {
      ++rays;
      const float tfar = isinf(dist) ? kInf : dist * (1.0 - 1e-4);
      vis = transmittance(offsetRayOrigin(s, wi), wi, tfar,
                          (whitted.flags & TD_WHITTED_TEXTURED_SHADOWS) != 0u);
    }
    culled += cls == 0 ? 1u : 0u;
    shadowLit += cls == 1 ? 1u : 0u;
    shadowShadowed += cls == 2 ? 1u : 0u;
    traced += cls == 3 ? 1u : 0u;
    c += term * vis;
  }
  return c;
}

struct Pending {  // a secondary ray and what its colour weighs in the pixel
  vec3 origin, dir, weight;
  int depth;
  float importance;
};
Pending stack[65];  // depth-first, two children a ray: at most max_depth + 1 wait
int stackSize = 0;

// Whitted::reflectionFrom and refractionFrom at s for a ray along d: the ray pushed with
// `weight` (refraction's tinted by the material's transmission filter).
void pushReflection(Surface s, vec3 d, vec3 weight, int depth, float importance) {
  const vec3 r = reflectionDir(s, d);
  stack[stackSize++] = Pending(offsetRayOrigin(s, r), r, weight, depth, importance);
}
void pushRefraction(Surface s, vec3 d, vec3 weight, int depth, float importance) {
  const vec3 r = refractionDir(s, d);
  const vec3 tint = v3(Materials(S.materials).m[s.material].transmissionFilter);
  stack[stackSize++] = Pending(offsetRayOrigin(s, r), r, weight * tint, depth, importance);
}

// Whitted::traceSecondary for every ray pushed, one at a time: the weighted sum of their colours.
vec3 traceStack() {
  vec3 color = vec3(0.0);
  while (stackSize > 0) {
    const Pending p = stack[--stackSize];
    ++rays;
    TraceHit g;
    if (!traverse(p.origin, p.dir, 0.0, 1e30, TRACE_FILTERED, g)) {
      color += p.weight * skyRadiance(p.dir);
      continue;
    }
    const Surface q = resolveSurface(g.object, g.prim, p.origin, p.dir, g.t, g.u, g.v, 0.0);
    const float qm = q.reflectivity, qr = 1.0 - q.opacity;
    float m, r, l;
    effectWeights(qm, qr, m, r, l);
    vec3 lighting = vec3(0.0);
    if (qm < 1.0 && qr < 1.0) lighting = shadeUnshadowed(q, -p.dir);
    if (p.depth >= whitted.maxDepth) {
      // Out of depth: the surface's own lighting stands in for both effects.
      if ((whitted.flags & TD_WHITTED_SHADE_AT_MAX_DEPTH) != 0u)
        lighting = shadeUnshadowed(q, -p.dir);
      color += p.weight * (m + r + l) * lighting;
      continue;
    }
    color += p.weight * l * lighting;
    if (p.importance * qr > whitted.importanceCutoff)
      pushRefraction(q, p.dir, p.weight * r, p.depth + 1, p.importance * qr);
    if (p.importance * qm > whitted.importanceCutoff)
      pushReflection(q, p.dir, p.weight * m, p.depth + 1, p.importance * qm);
  }
  return color;
}
