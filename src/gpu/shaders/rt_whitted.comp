#version 460
// rt_whitted on the GPU, one invocation a pixel, what RTWhittedPass::execute computes with every
// shadow traced: the camera ray (back faces of single-sided materials culled), the surface
// resolved at the pixel cone's texture level, shadow rays to the lights whose share of the
// surface's light reaches shadow_cull (Listing 8b's attenuation), and the reflection and
// refraction rays of Listings 8c/8d. The recursion runs as an explicit stack of weighted rays:
// eq. 5-6 are linear in the reflected, refracted and local colours, so each ray carries the
// weight its colour has in the pixel and adds its own lighting there.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "scene_data.h"
#include "whitted_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { WhittedArgs a; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Out { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Counts { uint v[]; };

#include "camera.glsl"
#include "scene.glsl"

uint rays = 0u, culled = 0u, traced = 0u;

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

// Lighting of a primary surface with its shadows (Whitted::shadePrimary8's shading, every
// shadow traced): a light below shadow_cull of the surface's unshadowed light is not asked about.
vec3 shadePrimary(Surface s, vec3 wo) {
  Lights lights = Lights(S.lights);
  const vec3 self = selfTerm(s);
  float floorShare = 0.0;
  if (a.shadowCull > 0.0) {
    vec3 total = self;
    for (uint i = 0u; i < S.lightCount; ++i) total += lightTerm(s, wo, lights.l[i]);
    floorShare = a.shadowCull * luminance(total);
  }
  vec3 c = self;
  for (uint i = 0u; i < S.lightCount; ++i) {
    const GpuLight l = lights.l[i];
    const vec3 term = lightTerm(s, wo, l);
    const float share = luminance(term);
    bool asked = a.shadowCull > 0.0 ? l.castsShadows != 0u && share > 0.0 && share >= floorShare
                                    : l.castsShadows != 0u;
    vec3 wi, radiance;
    float dist;
    sampleLight(l, s.position, wi, dist, radiance);
    asked = asked && dot(s.normal, wi) > 0.0 && maxComponent(radiance) > 0.0;
    vec3 vis = vec3(1.0);
    if (asked) {
      ++traced;
      ++rays;
      const float tfar = isinf(dist) ? kInf : dist * (1.0 - 1e-4);
      vis = transmittance(offsetRayOrigin(s, wi), wi, tfar,
                          (a.flags & TD_WHITTED_TEXTURED_SHADOWS) != 0u);
    } else {
      ++culled;
    }
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

void main() {
  const GpuCamera cam = CameraRef(a.camera).c;
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= cam.width || y >= cam.height) return;
  useScene(a.scene);
  const uint pixel = uint(y + a.viewY) * uint(a.frameWidth) + uint(x + a.viewX);
  vec3 origin, dir;
  float tnear;
  cameraRay(cam, x, y, origin, dir, tnear);
  TraceHit h;
  ++rays;
  const bool found = traverse(origin, dir, tnear, 1e30, TRACE_FILTERED | TRACE_CULL_BACK, h);
  Out(a.objectId).v[pixel] = found ? float(h.object) : -1.0;
  vec3 color;
  if (!found) {
    color = skyRadiance(dir);
  } else {
    const Surface s = resolveSurface(h.object, h.prim, origin, dir, h.t, h.u, h.v, cam.pixelSpread);
    const float om = s.reflectivity, orr = 1.0 - s.opacity;
    float wm, wr, wc;
    effectWeights(om, orr, wm, wr, wc);
    color = wc * shadePrimary(s, -dir);
    // Primary reflection and refraction have no cutoff (Whitted::primaryReflection).
    int size = 0;
    if (orr > 0.0) {
      const vec3 r = refractionDir(s, dir);
      const vec3 tint = v3(Materials(S.materials).m[s.material].transmissionFilter);
      stack[size++] = Pending(offsetRayOrigin(s, r), r, vec3(wr) * tint, 1, orr);
    }
    if (om > 0.0) {
      const vec3 r = reflectionDir(s, dir);
      stack[size++] = Pending(offsetRayOrigin(s, r), r, vec3(wm), 1, om);
    }
    // Whitted::traceSecondary, one ray at a time.
    while (size > 0) {
      const Pending p = stack[--size];
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
      if (p.depth >= a.maxDepth) {
        // Out of depth: the surface's own lighting stands in for both effects.
        if ((a.flags & TD_WHITTED_SHADE_AT_MAX_DEPTH) != 0u) lighting = shadeUnshadowed(q, -p.dir);
        color += p.weight * (m + r + l) * lighting;
        continue;
      }
      color += p.weight * l * lighting;
      if (p.importance * qr > a.importanceCutoff) {
        const vec3 d = refractionDir(q, p.dir);
        const vec3 tint = v3(Materials(S.materials).m[q.material].transmissionFilter);
        stack[size++] = Pending(offsetRayOrigin(q, d), d, p.weight * r * tint, p.depth + 1,
                                p.importance * qr);
      }
      if (p.importance * qm > a.importanceCutoff) {
        const vec3 d = reflectionDir(q, p.dir);
        stack[size++] = Pending(offsetRayOrigin(q, d), d, p.weight * m, p.depth + 1,
                                p.importance * qm);
      }
    }
  }
  Out(a.hdr).v[3u * pixel] = color.x;
  Out(a.hdr).v[3u * pixel + 1u] = color.y;
  Out(a.hdr).v[3u * pixel + 2u] = color.z;
  Counts counts = Counts(a.counters);
  atomicAdd(counts.v[TD_COUNT_RAYS], rays);
  if (found) {
    atomicAdd(counts.v[TD_COUNT_CULLED], culled);
    atomicAdd(counts.v[TD_COUNT_TRACED], traced);
    atomicAdd(counts.v[TD_COUNT_SURFACES], 1u);
  }
}
