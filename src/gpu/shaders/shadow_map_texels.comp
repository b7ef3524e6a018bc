#version 460
// shadow_map_texels: one rectangle of a face's texels, 8x8 a workgroup. Restore: the static
// casters' copy back into the maps (before moving casters are drawn again, as
// ShadowMaps::restoreStatic). Opaque: the depth where an opaque caster drew the map, else 0
// (ShadowMaps::markOpaque).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "scene_data.h"
#include "shadow_map_draw_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { uint64_t args; };

#include "scene.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ArgsRef {
  ShadowTexelArgs a;
};
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Keys { uint64_t v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer OpaqueDepth { float v[]; };

void main() {
  const ShadowTexelArgs a = ArgsRef(args).a;
  const int x = a.x0 + int(gl_GlobalInvocationID.x), y = a.y0 + int(gl_GlobalInvocationID.y);
  if (x >= a.x1 || y >= a.y1) return;
  const uint i = uint(y) * uint(a.width) + uint(x);
  if (a.mode == TD_TEXELS_RESTORE) {
    Keys(a.depth).v[i] = Keys(a.staticDepth).v[i];
    Keys(a.near).v[i] = Keys(a.staticNear).v[i];
    return;
  }
  useScene(a.scene);
  const uint64_t key = Keys(a.depth).v[i];
  float opaque = 0.0;
  if (key != 0ul) {
    const int object = objectOfTriangle(~uint(key), a.objectCount);
    if (Uints(a.opaqueCasters).v[object] != 0u) opaque = uintBitsToFloat(uint(key >> 32));
  }
  OpaqueDepth(a.opaque).v[i] = opaque;
}
