#version 460
// tonemap on the GPU: the CPU's tonemapSpan (core/tonemap_span.cpp) per value: exposure, the tone
// curve, the sRGB encoding; non-finite and negative values give 0.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "tonemap_args.h"

layout(local_size_x = 64) in;
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Floats { float v[]; };
layout(push_constant, scalar) uniform Push { TonemapArgs a; };

void main() {
  const uint i = gl_GlobalInvocationID.y * a.rowWidth + gl_GlobalInvocationID.x;
  if (i >= a.count) return;
  float v = Floats(a.hdr).v[i] * a.scale;
  v = (isnan(v) || isinf(v)) ? 0.0 : max(v, 0.0);
  if (a.op == 0u) {
    v = min(v, 1.0);
  } else if (a.op == 1u) {
    v = v / (1.0 + v);
  } else {  // Narkowicz's ACES fit x (a x + b) / (x (c x + d) + e)
    v = clamp(v * (2.51 * v + 0.03) / (v * (2.43 * v + 0.59) + 0.14), 0.0, 1.0);
  }
  const float curve = 1.055 * exp(log(max(v, 1e-30)) * (1.0 / 2.4)) - 0.055;
  Floats(a.display).v[i] = v <= 0.0031308 ? v * 12.92 : min(curve, 1.0);
}
