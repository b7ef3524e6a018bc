#version 460
// accumulation on the GPU, one invocation a pixel of one pair, what AccumulationPass::execute
// computes: the visible triangle (the compute rasterizer's, at the pair's time and lens point)
// intersected by the pixel's camera ray, shaded by Whitted's full shading (shadows, mirrors,
// glass) or local Blinn-Phong, the sky where nothing is drawn; added into hdr with the pair's
// weight, pairs in the CPU's order.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "accumulation_args.h"
#include "bvh.h"
#include "scene_data.h"
#include "shadow_maps_data.h"
#include "whitted_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { uint64_t args; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ArgsRef {
  AccumulationArgs a;
};
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer Keys {
  uint64_t v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Out { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Counts { uint v[]; };

AccumulationArgs A;

#include "camera.glsl"
#include "scene.glsl"
#include "shadow_maps.glsl"
#include "whitted.glsl"

void main() {
  A = ArgsRef(args).a;
  const GpuCamera cam = CameraRef(A.camera).c;
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= cam.width || y >= cam.height) return;
  useScene(A.scene);
  traceTau = A.tau;
  whitted = WhittedConfig(A.maxDepth, A.importanceCutoff, A.shadowCull, A.whittedFlags);
  vec3 origin, dir;
  float tnear;
  cameraRay(cam, x, y, origin, dir, tnear);
  const uint64_t key = Keys(A.visibility).v[uint(y) * uint(cam.width) + uint(x)];
  vec3 c;
  if (key == 0ul) {
    c = skyRadiance(dir);
  } else {
    const uint triangle = ~uint(key & 0xfffffffful);
    const int object = objectOfTriangle(triangle, A.objectCount);
    const GpuObject ob = Objects(S.objects).o[object];
    const int prim = int(triangle - ob.firstIndex / 3u);
    const uvec3 k = triangleVertices(ob, prim);
    float t, u, v;
    intersectTriangle(origin, dir, vertexPositionAt(ob, k.x), vertexPositionAt(ob, k.y),
                      vertexPositionAt(ob, k.z), t, u, v);
    const Surface s = resolveSurface(object, prim, origin, dir, t, u, v, 0.0);
    if (A.whittedShading != 0u) {
      const float om = s.reflectivity, orr = 1.0 - s.opacity;
      float wm, wr, wc;
      effectWeights(om, orr, wm, wr, wc);
      c = wc * shadePrimary(s, -dir);
      if (orr > 0.0) pushRefraction(s, dir, vec3(wr), 1, orr);
      if (om > 0.0) pushReflection(s, dir, vec3(wm), 1, om);
      c += traceStack();
    } else {
      c = shadeUnshadowed(s, -dir);
    }
  }
  Out hdr = Out(A.hdr);
  const uint at = 3u * (uint(y + A.viewY) * A.frameWidth + uint(x + A.viewX));
  hdr.v[at] += c.x * A.weight;
  hdr.v[at + 1u] += c.y * A.weight;
  hdr.v[at + 2u] += c.z * A.weight;
  if (rays > 0u) atomicAdd(Counts(A.counters).v[0], rays);
}
