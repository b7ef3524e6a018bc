#version 460
// rt_whitted on the GPU, one invocation a pixel, what RTWhittedPass::execute computes: the camera
// ray (back faces of single-sided materials culled), the surface resolved at the pixel cone's
// texture level, shadows of the lights whose share of the surface's light reaches shadow_cull
// (Listing 8b's attenuation; traced, classified by the frame's shadow maps, or looked up in them),
// and the reflection and
// refraction rays of Listings 8c/8d (whitted.glsl).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "scene_data.h"
#include "shadow_maps_data.h"
#include "whitted_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { WhittedArgs a; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Out { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Counts { uint v[]; };

#include "camera.glsl"
#include "scene.glsl"
#include "shadow_maps.glsl"
#include "whitted.glsl"

void main() {
  const GpuCamera cam = CameraRef(a.camera).c;
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= cam.width || y >= cam.height) return;
  useScene(a.scene);
  if (a.shadowMaps != 0ul) useShadowMaps(a.shadowMaps);
  whitted = WhittedConfig(a.maxDepth, a.importanceCutoff, a.shadowCull, a.flags);
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
    if (orr > 0.0) pushRefraction(s, dir, vec3(wr), 1, orr);
    if (om > 0.0) pushReflection(s, dir, vec3(wm), 1, om);
    color += traceStack();
  }
  Out(a.hdr).v[3u * pixel] = color.x;
  Out(a.hdr).v[3u * pixel + 1u] = color.y;
  Out(a.hdr).v[3u * pixel + 2u] = color.z;
  Counts counts = Counts(a.counters);
  atomicAdd(counts.v[TD_COUNT_RAYS], rays);
  if (found) {
    atomicAdd(counts.v[TD_COUNT_CULLED], culled);
    atomicAdd(counts.v[TD_COUNT_TRACED], traced);
    if (shadowLit > 0u) atomicAdd(counts.v[TD_COUNT_LIT], shadowLit);
    if (shadowShadowed > 0u) atomicAdd(counts.v[TD_COUNT_SHADOWED], shadowShadowed);
    atomicAdd(counts.v[TD_COUNT_SURFACES], 1u);
  }
}
