#version 460
// blend on the GPU, pixel for pixel what BlendPass::execute computes (Walewski et al. 2019
// Listing 10): outside the mask the lighting L; inside, C = L - (1 - S) (eq. 4) and the average of
// C_M and C_R (eq. 5-6), an effect not traced standing absent unless the fallback covers it.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "blend_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { BlendArgs a; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Floats { float v[]; };

vec3 load3(uint64_t b, uint i) {
  Floats f = Floats(b);
  return vec3(f.v[i], f.v[i + 1u], f.v[i + 2u]);
}

// combineEffects (rt/whitted.cpp), in its order of operations.
vec3 combineEffects(float om, float orr, vec3 m, vec3 r, vec3 c) {
  const vec3 cm = m * om + (r * orr + c * (1.0 - orr)) * (1.0 - om);
  const vec3 cr = r * orr + (m * om + c * (1.0 - om)) * (1.0 - orr);
  return (cm + cr) * 0.5;
}

void main() {
  const uint x = gl_GlobalInvocationID.x, y = gl_GlobalInvocationID.y;
  if (x >= a.width || y >= a.height) return;
  const uint i = y * a.width + x;
  const vec3 m = load3(a.mask, 3u * i);
  const uint fb = TD_FALLBACK_CHANNELS * i;
  const bool hasFallback =
      a.fallback != 0ul && Floats(a.fallback).v[fb + TD_FALLBACK_COVERS_EFFECT] > 0.5;
  const bool hasShadowFallback =
      a.fallback != 0ul && Floats(a.fallback).v[fb + TD_FALLBACK_COVERS_SHADOW] > 0.5;
  const vec3 L = load3(a.hdr, 3u * i);
  vec3 c = L;
  if (m.x >= 0.5 || m.y >= 0.5 || m.z >= 0.5 || hasFallback || hasShadowFallback) {
    const vec3 op = load3(a.optical, 3u * i);  // reflectivity, ior, opacity
    const bool traceM = m.y > 0.5, traceR = m.z > 0.5;
    const float om = traceM || hasFallback ? op.x : 0.0;
    const float orr = traceR || hasFallback ? 1.0 - op.z : 0.0;
    const vec3 refl = traceM        ? load3(a.reflection, 3u * i)
                      : hasFallback ? load3(a.fallback, fb + TD_FALLBACK_REFLECTION)
                                    : vec3(0.0);
    const vec3 refr = traceR        ? load3(a.refraction, 3u * i)
                      : hasFallback ? load3(a.fallback, fb + TD_FALLBACK_REFRACTION)
                                    : vec3(0.0);
    if (m.x > 0.5)
      c = c - (vec3(1.0) - load3(a.shadow, 3u * i));  // eq. 4
    else if (hasShadowFallback)
      c = c - (vec3(1.0) - load3(a.fallback, fb + TD_FALLBACK_SHADOW));
    c = combineEffects(om, orr, refl, refr, c);
  }
  Floats composite = Floats(a.composite);
  composite.v[3u * i] = c.x;
  composite.v[3u * i + 1u] = c.y;
  composite.v[3u * i + 2u] = c.z;
}
