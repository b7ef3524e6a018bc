#version 460
// One pass of a separable filter, as convolve1d (core/image_filters.cpp) computes it: each output
// value the taps' weighted sum in the order of the taps, the edges clamped.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "dof_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { ConvolveArgs a; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Floats { float v[]; };

void main() {
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  const int W = int(a.width), H = int(a.height), C = int(a.channels), r = int(a.radius);
  if (x >= W || y >= H) return;
  Floats src = Floats(a.src), w = Floats(a.weights);
  for (int c = 0; c < C; ++c) {
    precise float sum = 0.0;
    for (int t = -r; t <= r; ++t) {
      const float k = w.v[t + r];
      if (k == 0.0) continue;
      const int sx = a.horizontal != 0u ? clamp(x + t, 0, W - 1) : x;
      const int sy = a.horizontal != 0u ? y : clamp(y + t, 0, H - 1);
      sum += k * src.v[uint((sy * W + sx) * C + c)];
    }
    Floats(a.dst).v[uint((y * W + x) * C + c)] = sum;
  }
}
