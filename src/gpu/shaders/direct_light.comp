#version 460
// direct_light on the GPU, one invocation a pixel of a view, what DirectLightPass::execute
// computes: the primary surface's emission plus its albedo times the light of the `count` lights
// giving it the most unshadowed light, each with its shadow ray (giBrightestDirect); the sky
// through the pixel's centre where there is no surface.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "foveated_args.h"
#include "scene_data.h"
#include "whitted_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push {
  uint64_t args;
  uint view;
};
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ArgsRef {
  DirectLightArgs a;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Out { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Counts { uint v[]; };

DirectLightArgs A;

#include "camera.glsl"
#include "scene.glsl"
#include "whitted.glsl"
#include "diffuse_gi.glsl"
#include "primary_surface.glsl"

void main() {
  A = ArgsRef(args).a;
  const FoveatedView v = FoveatedViews(A.views).v[view];
  const int ex = int(gl_GlobalInvocationID.x), ey = int(gl_GlobalInvocationID.y);
  if (ex >= v.width || ey >= v.height) return;
  useScene(A.scene);
  giGrid = A.lights;
  const uint i = uint(ey + v.y) * A.frameWidth + uint(ex + v.x);
  vec3 L;
  if (gbufferSky(A.g, i)) {  // the sky, as foveated_pt sees it
    vec3 o, d;
    float tnear;
    cameraRay(v.camera, ex, ey, o, d, tnear);
    L = skyRadiance(d);
  } else {
    const Surface s = gbufferSurface(A.g, i);
    const vec3 wo = towardsViewer(v, s.position);
    L = giEmitted(s, wo) + giAlbedo(s) * giBrightestDirect(s, wo, A.count);
  }
  Out out3 = Out(A.direct);
  out3.v[3u * i] = L.x;
  out3.v[3u * i + 1u] = L.y;
  out3.v[3u * i + 2u] = L.z;
  atomicAdd(Counts(A.counters).v[TD_FOVEATED_RAYS], rays);
}
