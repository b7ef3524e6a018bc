#version 460
// raster_pack: the graphics pipeline's attachments (copied into buffers) packed into the compute
// rasterizer's visibility keys, depth bits over the triangle's complement (raster_args.h), so the
// same resolve follows either rasterizer.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "raster_graphics_args.h"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { RasterPackArgs a; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Uints { uint v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Floats { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Keys { uint64_t v[]; };

void main() {
  const uint i = gl_GlobalInvocationID.y * 65535u * 64u + gl_GlobalInvocationID.x;
  if (i >= a.pixels) return;
  const uint id = Uints(a.ids).v[i];
  Keys(a.visibility).v[i] =
      id == 0u ? 0ul
               : (uint64_t(floatBitsToUint(Floats(a.depths).v[i])) << 32) | uint64_t(~(id - 1u));
}
