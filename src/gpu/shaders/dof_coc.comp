#version 460
// dof_coc on the GPU, as DofCocPass::execute: each pixel's signed circle of confusion from the
// view's thin lens (ThinLens::coc, Tan et al. 2022 eq. 6); the sky's the far-field limit.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "dof_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { DofCocArgs a; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Floats { float v[]; };

void main() {
  const uint x = gl_GlobalInvocationID.x, y = gl_GlobalInvocationID.y;
  if (x >= a.width || y >= a.height) return;
  const uint i = (a.viewY + y) * a.frameWidth + a.viewX + x;
  precise float c = 0.0;
  if (a.lensActive != 0u) {
    const float k = a.aperture * a.pixelsPerSlope;
    if (Floats(a.depth).v[i] > 0.0) {
      Floats p = Floats(a.position);
      precise const float dx = p.v[3u * i] - a.eyeX, dy = p.v[3u * i + 1u] - a.eyeY,
                          dz = p.v[3u * i + 2u] - a.eyeZ;
      precise const float z = dx * a.forwardX + dy * a.forwardY + dz * a.forwardZ;
      c = k * (z - a.focus) / (max(z, 1e-6) * a.focus);
    } else {
      c = k / a.focus;
    }
  }
  Floats(a.coc).v[i] = c;
}
