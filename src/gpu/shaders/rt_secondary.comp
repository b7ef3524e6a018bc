#version 460
// rt_secondary on the GPU, one invocation a pixel, what RTSecondaryPass::execute computes with
// every shadow traced (Walewski et al. 2019 Listing 8a from the G-buffer): for the effects the
// heuristic mask selects, S = 1 - the light the occluders block (the lights whose share of the
// surface's light reaches shadow_cull asked, as classifiedShadowTile asks them), and the primary
// reflection and refraction with their recursion (whitted.glsl). Each object's pixels and rays
// per effect are tallied for rt_stats.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "gbuffer_args.h"
#include "scene_data.h"
#include "secondary_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { SecondaryArgs a; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Counts { uint v[]; };

#include "camera.glsl"
#include "scene.glsl"
#include "gbuffer.glsl"
#include "whitted.glsl"

// Listing 8a's S at s seen along wo: 1 minus each asked light's term times what blocks it.
vec3 shadowTerm(Surface s, vec3 wo, out bool classAsked) {
  Lights lights = Lights(S.lights);
  vec3 total = selfTerm(s);
  for (uint i = 0u; i < S.lightCount; ++i) total += lightTerm(s, wo, lights.l[i]);
  const float floorShare = a.shadowCull * luminance(total);
  vec3 blocked = vec3(0.0);
  classAsked = false;
  for (uint i = 0u; i < S.lightCount; ++i) {
    const GpuLight l = lights.l[i];
    const vec3 term = lightTerm(s, wo, l);
    const float share = luminance(term);
    if (!(l.castsShadows != 0u && share > 0.0 && share >= floorShare)) {
      ++culled;
      continue;
    }
    ++traced;
    ++rays;
    if (a.classLight < 0 || uint(a.classLight) == i) classAsked = true;
    vec3 wi, radiance;
    float dist;
    sampleLight(l, s.position, wi, dist, radiance);
    const float tfar = isinf(dist) ? kInf : dist * (1.0 - 1e-4);
    const vec3 vis = transmittance(offsetRayOrigin(s, wi), wi, tfar,
                                   (a.flags & TD_WHITTED_TEXTURED_SHADOWS) != 0u);
    blocked += term * (vec3(1.0) - vis);
  }
  return vec3(1.0) - blocked;
}

void main() {
  const GpuView view = ViewRef(a.view).v;
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= view.camera.width || y >= view.camera.height) return;
  useScene(a.scene);
  whitted = WhittedConfig(a.maxDepth, a.importanceCutoff, a.shadowCull, a.flags);
  const uint pixel = uint(y + a.viewY) * uint(a.frameWidth) + uint(x + a.viewX);
  const vec3 m = get3(a.mask, pixel);
  const bool wantShadow = m.x > 0.5, wantReflection = m.y > 0.5, wantRefraction = m.z > 0.5;
  Surface s;
  const bool hit = (wantShadow || wantReflection || wantRefraction) &&
                   readSurface(TargetsRef(a.sources).g, pixel, s);
  vec3 shadow = vec3(hit ? 1.0 : a.outsideShadow), reflection = vec3(0.0), refraction = vec3(0.0);
  vec3 shadowClass = vec3(0.0);
  uint tally[TD_STATS_PER_OBJECT] = uint[](0u, 0u, 0u, 0u, 0u, 0u);
  if (hit) {
    vec3 origin, dir;
    float tnear;
    cameraRay(view.camera, x, y, origin, dir, tnear);
    if (wantShadow) {
      // The eye direction as deferred shading takes it.
      const vec3 eye = vec3(view.camera.eye[0], view.camera.eye[1], view.camera.eye[2]);
      const vec3 forward =
          vec3(view.camera.forward[0], view.camera.forward[1], view.camera.forward[2]);
      bool asked;
      shadow = shadowTerm(s, view.perspective != 0 ? safeNormalize(eye - s.position) : -forward,
                          asked);
      shadowClass = vec3(asked ? 1.0 : 0.0, 0.0, 0.0);  // every asked light is traced
      tally[0] = 1u;
      tally[3] = rays;
    }
    if (wantReflection && s.reflectivity > 0.0) {
      const uint before = rays;
      pushReflection(s, dir, vec3(1.0), 1, s.reflectivity);
      reflection = traceStack();
      tally[1] = 1u;
      tally[4] = rays - before;
    }
    if (wantRefraction && s.opacity < 1.0) {
      const uint before = rays;
      pushRefraction(s, dir, vec3(1.0), 1, 1.0 - s.opacity);
      refraction = traceStack();
      tally[2] = 1u;
      tally[5] = rays - before;
    }
  }
  put3(a.shadow, pixel, shadow);
  put3(a.reflection, pixel, reflection);
  put3(a.refraction, pixel, refraction);
  put3(a.traced, pixel, vec3(wantShadow ? 1.0 : 0.0, wantReflection ? 1.0 : 0.0,
                             wantRefraction ? 1.0 : 0.0));
  if (a.shadowClass != 0ul) put3(a.shadowClass, pixel, shadowClass);
  Counts counts = Counts(a.counters);
  if (rays > 0u) atomicAdd(counts.v[TD_COUNT_RAYS], rays);
  if (hit && wantShadow) {
    atomicAdd(counts.v[TD_COUNT_CULLED], culled);
    atomicAdd(counts.v[TD_COUNT_TRACED], traced);
    atomicAdd(counts.v[TD_COUNT_SURFACES], 1u);
  }
  if (hit) {
    Counts stats = Counts(a.stats);
    const uint at = uint(s.object) * uint(TD_STATS_PER_OBJECT);
    for (int k = 0; k < TD_STATS_PER_OBJECT; ++k)
      if (tally[k] != 0u) atomicAdd(stats.v[at + uint(k)], tally[k]);
  }
}
