// The kernels of trace_closest.comp (TRACE_KIND 0: the nearest hit) and trace_any.comp
// (TRACE_KIND TRACE_ANY: the first hit found, for occlusion) over a batch of rays: both faces
// hit, no filter, as RayTracer::intersect without culling.

layout(local_size_x = 64) in;
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Rays { GpuRay r[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer Hits { GpuHit h[]; };
layout(push_constant, scalar) uniform Push { TraceArgs a; };

#include "traverse.glsl"

int hitFilter(uint flags, int object, int prim, float t, float u, float v, vec3 ng, vec3 o,
              vec3 d) {
  return HIT_ACCEPT;
}

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= a.count) return;
  bvh = BvhRefs(a.nodes, a.triangles, a.trianglePrim, a.objectRoot, a.topRoot, a.objectMotion,
                a.motionTriangles);
  const GpuRay ray = Rays(a.rays).r[i];
  TraceHit h;
  traverse(vec3(ray.ox, ray.oy, ray.oz), vec3(ray.dx, ray.dy, ray.dz), ray.tnear, ray.tfar,
           TRACE_KIND, h);
  Hits(a.hits).h[i] = GpuHit(h.t, h.u, h.v, h.object, h.prim, 0u, 0u, 0u);
}
