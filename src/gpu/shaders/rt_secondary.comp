#version 460
// rt_secondary on the GPU, one invocation a pixel, what RTSecondaryPass::execute computes
// (Walewski et al. 2019 Listing 8a from the G-buffer): for the effects the heuristic mask
// selects, S = 1 - the light the occluders block (shadow_term.glsl: shadow rays, classified
// shadows or shadow maps, as classifiedShadowTile decides them), and the primary
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
#include "shadow_maps_data.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { SecondaryArgs a; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Counts { uint v[]; };

#include "camera.glsl"
#include "scene.glsl"
#include "gbuffer.glsl"
#include "shadow_maps.glsl"
#include "whitted.glsl"
#include "shadow_term.glsl"

void main() {
  const GpuView view = ViewRef(a.view).v;
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= view.camera.width || y >= view.camera.height) return;
  useScene(a.scene);
  if (a.shadowMaps != 0ul) useShadowMaps(a.shadowMaps);
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
      shadow = shadowTerm(s, view.perspective != 0 ? safeNormalize(eye - s.position) : -forward,
                          a.classLight, shadowClass);
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
    if (shadowLit > 0u) atomicAdd(counts.v[TD_COUNT_LIT], shadowLit);
    if (shadowShadowed > 0u) atomicAdd(counts.v[TD_COUNT_SHADOWED], shadowShadowed);
    atomicAdd(counts.v[TD_COUNT_SURFACES], 1u);
  }
  if (hit) {
    const uint at = uint(TD_COUNT_N) + uint(s.object) * uint(TD_STATS_PER_OBJECT);
    for (int k = 0; k < TD_STATS_PER_OBJECT; ++k)
      if (tally[k] != 0u) atomicAdd(counts.v[at + uint(k)], tally[k]);
  }
}
