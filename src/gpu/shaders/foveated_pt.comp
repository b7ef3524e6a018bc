#version 460
// foveated_pt on the GPU, one invocation a listed pixel of an eye, what FoveatedPTPass::execute
// computes: the pixel's samples (the CPU's Owen-scrambled Sobol points, seeded per frame) of
// DiffuseGI::radiance from the G-buffer's surface (diffuse_gi.glsl), their mean into pt_noisy and
// the variance of that mean's luminance into pt_variance (-1 from one sample); the sky through
// the pixel's centre where there is no surface. Entry k is coordinate k % listed of eye
// k / listed.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "foveated_args.h"
#include "scene_data.h"
#include "whitted_args.h"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { uint64_t args; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ArgsRef {
  FoveatedPtArgs a;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Out { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Counts { uint v[]; };

FoveatedPtArgs A;

#include "camera.glsl"
#include "scene.glsl"
#include "whitted.glsl"
#include "diffuse_gi.glsl"
#include "primary_surface.glsl"
#include "sobol.glsl"

const uint kRowEntries = 64u * 64u;  // entries per row of groups (the host's dispatch)

void main() {
  A = ArgsRef(args).a;
  const uint k = gl_GlobalInvocationID.y * kRowEntries + gl_GlobalInvocationID.x;
  if (k >= A.listed * A.viewCount) return;
  useScene(A.scene);
  giGrid = A.grid;
  const FoveatedView v = FoveatedViews(A.views).v[k / A.listed];
  Out coords = Out(A.coords);
  const uint c = 3u * (k % A.listed);  // CoordChannels: x, y, spp
  const int ex = int(coords.v[c]), ey = int(coords.v[c + 1u]), spp = int(coords.v[c + 2u]);
  if (ex >= v.width || ey >= v.height) return;
  const int x = ex + v.x, y = ey + v.y;
  const uint i = uint(y) * A.frameWidth + uint(x);
  vec3 sum = vec3(0.0);
  float lum2 = 0.0;  // the samples' squared luminances
  if (gbufferSky(A.g, i)) {
    vec3 o, d;
    float tnear;
    cameraRay(v.camera, ex, ey, o, d, tnear);
    sum = skyRadiance(d) * float(spp);
  } else {
    const Surface s = gbufferSurface(A.g, i);
    const vec3 wo = towardsViewer(v, s.position);
    const uint64_t seed = (uint64_t(A.seedHi) << 32) | uint64_t(A.seedLo);
    const uint64_t pixel = uint64_t(y) * uint64_t(A.frameWidth) + uint64_t(x);
    for (int n = 0; n < spp; ++n) {
      startSampler(seed, pixel, uint(n));
      const vec2 u0 = uniform2(), u1 = uniform2(), u2 = uniform2();
      const vec3 L = giRadiance(s, wo, u0, u1, u2);
      if (any(isnan(L)) || any(isinf(L))) continue;
      sum += L;
      lum2 += luminance(L) * luminance(L);
    }
  }
  const float n = float(max(spp, 1));
  Out noisy = Out(A.noisy);
  const vec3 mean3 = sum / n;
  noisy.v[3u * i] = mean3.x;
  noisy.v[3u * i + 1u] = mean3.y;
  noisy.v[3u * i + 2u] = mean3.z;
  // The variance of the mean's luminance from the samples' spread; unknown (-1) from one.
  const float mean = luminance(sum) / n;
  Out(A.variance).v[i] = spp >= 2 ? max(lum2 - n * mean * mean, 0.0) / ((n - 1.0) * n) : -1.0;
  Counts counts = Counts(A.counters);
  atomicAdd(counts.v[TD_FOVEATED_RAYS], rays);
  atomicAdd(counts.v[TD_FOVEATED_SAMPLES], uint(spp));
}
