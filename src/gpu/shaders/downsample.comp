#version 460
// downsample on the GPU, one invocation a pixel of the smaller image: what core/image_filters.cpp
// computes, downsampleBox (the mean of a 2x2 block, what an odd edge leaves of it) or
// resizeBilinear (sampleBilinear at the pixel's centre scaled into the source, edges clamped).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "downsample_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { DownsampleArgs a; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Floats { float v[]; };

float texel(int x, int y, uint c) {
  return Floats(a.src).v[(uint(y) * uint(a.srcWidth) + uint(x)) * a.channels + c];
}

void main() {
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= a.dstWidth || y >= a.dstHeight) return;
  Floats dst = Floats(a.dst);
  const uint at = (uint(y) * uint(a.dstWidth) + uint(x)) * a.channels;
  if (a.mode == TD_DOWNSAMPLE_BOX) {
    const int xa = 2 * x, ya = 2 * y, xb = min(xa + 1, a.srcWidth - 1),
              yb = min(ya + 1, a.srcHeight - 1);
    const float n = float((xb - xa + 1) * (yb - ya + 1));
    for (uint c = 0u; c < a.channels; ++c) {
      precise float s = texel(xa, ya, c);
      if (xb != xa) s += texel(xb, ya, c);
      if (yb != ya) s += texel(xa, yb, c);
      if (xb != xa && yb != ya) s += texel(xb, yb, c);
      dst.v[at + c] = s / n;
    }
    return;
  }
  precise const float sx = float(a.srcWidth) / float(a.dstWidth);
  precise const float sy = float(a.srcHeight) / float(a.dstHeight);
  precise const float fx = (float(x) + 0.5) * sx - 0.5, fy = (float(y) + 0.5) * sy - 0.5;
  const int x0 = int(floor(fx)), y0 = int(floor(fy));
  precise const float tx = fx - float(x0), ty = fy - float(y0);
  const int xa = clamp(x0, 0, a.srcWidth - 1), xb = clamp(x0 + 1, 0, a.srcWidth - 1);
  const int ya = clamp(y0, 0, a.srcHeight - 1), yb = clamp(y0 + 1, 0, a.srcHeight - 1);
  for (uint c = 0u; c < a.channels; ++c) {
    precise const float v = (texel(xa, ya, c) * (1.0 - tx) + texel(xb, ya, c) * tx) * (1.0 - ty) +
                            (texel(xa, yb, c) * (1.0 - tx) + texel(xb, yb, c) * tx) * ty;
    dst.v[at + c] = v;
  }
}
