// The two-level BVH traversal of shaders/bvh.h, included by trace_closest.comp (TRACE_ANY 0: the
// nearest hit) and trace_any.comp (TRACE_ANY 1: the first hit found, for occlusion). Both faces
// hit, as RayTracer::intersect without culling; u and v are the barycentrics of v1 and v2, as
// Embree's.

layout(local_size_x = 64) in;
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Nodes { BvhNode n[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Floats { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Uints { uint v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Rays { GpuRay r[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer Hits { GpuHit h[]; };
layout(push_constant, scalar) uniform Push { TraceArgs a; };

// Entry distance into node n's box within [tnear, tfar], or -1 when the ray misses it (an empty
// box, lo > hi, is always missed).
float enter(BvhNode n, vec3 o, vec3 inv, float tnear, float tfar) {
  if (n.lox > n.hix) return -1.0;
  const vec3 t0 = (vec3(n.lox, n.loy, n.loz) - o) * inv;
  const vec3 t1 = (vec3(n.hix, n.hiy, n.hiz) - o) * inv;
  const vec3 lo = min(t0, t1), hi = max(t0, t1);
  const float t = max(max(lo.x, lo.y), max(lo.z, tnear));
  const float u = min(min(hi.x, hi.y), min(hi.z, tfar));
  return t <= u ? t : -1.0;
}

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= a.count) return;
  const GpuRay ray = Rays(a.rays).r[i];
  const vec3 o = vec3(ray.ox, ray.oy, ray.oz), d = vec3(ray.dx, ray.dy, ray.dz);
  // Zero components become huge: the slabs stay correct for axis-parallel rays.
  const vec3 inv = vec3(1.0) / mix(d, vec3(1e-30), equal(d, vec3(0.0)));
  Nodes nodes = Nodes(a.nodes);
  Floats tris = Floats(a.triangles);
  Uints roots = Uints(a.objectRoot);
  float best = ray.tfar, bu = 0.0, bv = 0.0;
  int bestObject = -1;
  uint bestTri = 0u;

  uint top[64], bottom[64];
  int topSize = 0;
  top[topSize++] = a.topRoot;
  while (topSize > 0) {
    const BvhNode n = nodes.n[top[--topSize]];
    if (enter(n, o, inv, ray.tnear, best) < 0.0) continue;
    if (n.count == 0u) {
      top[topSize++] = n.a;
      top[topSize++] = n.a + 1u;
      continue;
    }
    for (uint k = 0u; k < n.count; ++k) {
      const uint object = roots.v[n.a + k];
      int size = 0;
      bottom[size++] = roots.v[object];
      while (size > 0) {
        const BvhNode m = nodes.n[bottom[--size]];
        if (enter(m, o, inv, ray.tnear, best) < 0.0) continue;
        if (m.count == 0u) {
          bottom[size++] = m.a;
          bottom[size++] = m.a + 1u;
          continue;
        }
        for (uint t = m.a; t < m.a + m.count; ++t) {
          // Moller-Trumbore.
          const vec3 v0 = vec3(tris.v[9u * t], tris.v[9u * t + 1u], tris.v[9u * t + 2u]);
          const vec3 e1 = vec3(tris.v[9u * t + 3u], tris.v[9u * t + 4u], tris.v[9u * t + 5u]) - v0;
          const vec3 e2 = vec3(tris.v[9u * t + 6u], tris.v[9u * t + 7u], tris.v[9u * t + 8u]) - v0;
          const vec3 p = cross(d, e2);
          const float det = dot(e1, p);
          if (det == 0.0) continue;
          const float invDet = 1.0 / det;
          const vec3 s = o - v0;
          const float u = dot(s, p) * invDet;
          if (u < 0.0 || u > 1.0) continue;
          const vec3 q = cross(s, e1);
          const float v = dot(d, q) * invDet;
          if (v < 0.0 || u + v > 1.0) continue;
          const float th = dot(e2, q) * invDet;
          if (th < ray.tnear || th > best) continue;
#if TRACE_ANY
          Hits(a.hits).h[i] = GpuHit(th, u, v, int(object), int(Uints(a.trianglePrim).v[t]), 0u, 0u, 0u);
          return;
#endif
          best = th;
          bu = u;
          bv = v;
          bestObject = int(object);
          bestTri = t;
        }
      }
    }
  }
  GpuHit h;
  h.t = bestObject >= 0 ? best : 0.0;
  h.u = bu;
  h.v = bv;
  h.object = bestObject;
  h.prim = bestObject >= 0 ? int(Uints(a.trianglePrim).v[bestTri]) : -1;
  h.pad0 = h.pad1 = h.pad2 = 0u;
  Hits(a.hits).h[i] = h;
}
