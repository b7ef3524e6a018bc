#version 460
// heuristic on the GPU: countObjectPixels (mode TD_HEURISTIC_COUNT) and writeMask
// (TD_HEURISTIC_MASK) of HeuristicPass, one invocation a pixel; the selection between them (a
// few hundred nodes) is the host's.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "heuristic_args.h"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { HeuristicArgs a; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Floats { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Uints { uint v[]; };

void main() {
  const uint i = gl_GlobalInvocationID.y * a.rowWidth + gl_GlobalInvocationID.x;
  if (i >= a.pixelCount) return;
  const float id = Floats(a.objectId).v[i];
  const bool shows = id >= 0.0 && uint(id) < a.objectCount;
  if (a.mode == TD_HEURISTIC_COUNT) {
    if (shows) atomicAdd(Uints(a.pixels).v[uint(id)], 1u);
    return;
  }
  const uint bits = shows ? Uints(a.selected).v[uint(id)] : 0u;
  Floats mask = Floats(a.mask);
  for (uint k = 0u; k < 3u; ++k) mask.v[3u * i + k] = float((bits >> k) & 1u);
}
