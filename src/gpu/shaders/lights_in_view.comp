#version 460
// lightsInView on the GPU (passes/common/lights_in_view.cpp): which lights may light a surface the
// G-buffer shows, so that shadow maps are drawn only for them. A workgroup takes an 8x8 tile of
// one view, bounds its surfaces' positions, and tests each light against the box as
// lightsReaching does (a range, a spot's cone); a light that reaches it is flagged (plain stores
// of 1: any order gives the same flags).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "gbuffer_args.h"
#include "scene_data.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push {
  uint64_t scene, sources, flags;  // flags: a uint per light
  int viewX, viewY, viewWidth, viewHeight, frameWidth, pad;
} a;
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Flags { uint v[]; };

#include "scene.glsl"
#include "gbuffer.glsl"

// Floats as uints that keep their order (for atomicMin / atomicMax).
uint orderedBits(float f) {
  const uint u = floatBitsToUint(f);
  return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}
float fromOrdered(uint u) {
  return uintBitsToFloat((u & 0x80000000u) != 0u ? u & 0x7fffffffu : ~u);
}

shared uint lo[3], hi[3];
shared uint any;

void main() {
  const uint t = gl_LocalInvocationIndex;
  if (t == 0u) {
    for (int k = 0; k < 3; ++k) lo[k] = 0xffffffffu, hi[k] = 0u;
    any = 0u;
  }
  barrier();
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  const GBufferTargets g = TargetsRef(a.sources).g;
  if (x < a.viewWidth && y < a.viewHeight) {
    const uint pixel = uint(y + a.viewY) * uint(a.frameWidth) + uint(x + a.viewX);
    if (Target(g.objectId).v[pixel] >= 0.0) {
      const vec3 p = get3(g.position, pixel);
      for (int k = 0; k < 3; ++k) {
        atomicMin(lo[k], orderedBits(p[k]));
        atomicMax(hi[k], orderedBits(p[k]));
      }
      any = 1u;
    }
  }
  barrier();
  if (any == 0u) return;
  useScene(a.scene);
  const vec3 bl = vec3(fromOrdered(lo[0]), fromOrdered(lo[1]), fromOrdered(lo[2]));
  const vec3 bh = vec3(fromOrdered(hi[0]), fromOrdered(hi[1]), fromOrdered(hi[2]));
  const vec3 centre = (bl + bh) * 0.5;
  const float radius = 0.5 * length(bh - bl);
  Lights lights = Lights(S.lights);
  Flags flags = Flags(a.flags);
  for (uint i = t; i < S.lightCount; i += 64u) {
    const GpuLight l = lights.l[i];
    bool reaches = true;
    if (l.type != 0u && (l.range > 0.0 || l.type == 2u)) {
      const vec3 v = centre - v3(l.position);
      const float dist = length(v);
      if (l.range > 0.0 && dist > l.range + radius) reaches = false;
      // A spot: the box's bounding sphere must overlap the outer cone.
      if (reaches && l.type == 2u && l.hemisphere == 0u && dist > radius) {
        const float angle = acos(clamp(dot(v, v3(l.direction)) / dist, -1.0, 1.0));
        const float outer = acos(clamp(l.cosOuter, -1.0, 1.0));
        reaches = angle <= outer + asin(min(radius / dist, 1.0)) + 1e-3;
      }
    }
    if (reaches) flags.v[i] = 1u;
  }
}
