// The two-level BVH traversal of bvh.h as a function. u and v are the barycentrics of v1 and v2,
// as Embree's. The including kernel sets `bvh` and defines hitFilter (called only with
// TRACE_FILTERED), which decides per candidate hit as Embree's filter callbacks do for RayTracer.

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Nodes { BvhNode n[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Floats { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Uints { uint v[]; };

// Flags of traverse().
const uint TRACE_ANY = 1u;       // the first hit accepted ends the ray (occlusion)
const uint TRACE_ALL = 2u;       // every hit up to tfar goes to the filter, none shortens the ray
const uint TRACE_FILTERED = 4u;  // candidate hits go through hitFilter
// What hitFilter says of a candidate.
const int HIT_ACCEPT = 0, HIT_IGNORE = 1, HIT_STOP = 2;

struct BvhRefs {
  uint64_t nodes, triangles, trianglePrim, objectRoot;
  uint topRoot;
  uint64_t objectMotion, motionTriangles;
};
BvhRefs bvh;
// The shutter fraction in [0, 1] of the rays traced (Ray::time): where moving objects are met.
// A kernel tracing an open shutter sets it per sample; 0 (shutter open) otherwise.
float traceTau = 0.0;

struct TraceHit {
  float t, u, v;
  int object, prim;  // object -1: no hit
};

// `ng`: the triangle's unnormalised geometric normal, cross(v1 - v0, v2 - v0).
int hitFilter(uint flags, int object, int prim, float t, float u, float v, vec3 ng, vec3 o,
              vec3 d);

// Triangle (v0, v1, v2) against the ray within [tnear, tfar] (Moller-Trumbore, both faces). ng:
// cross(v1 - v0, v2 - v0), unnormalised. Where two surfaces meet (a corner of two walls) the
// distances to both agree within rounding, and which one a ray takes may differ from Embree's.
bool hitTriangle(vec3 v0, vec3 v1, vec3 v2, vec3 o, vec3 d, float tnear, float tfar,
                 out float th, out float u, out float v, out vec3 ng) {
  th = u = v = 0.0;
  const vec3 e1 = v1 - v0;
  const vec3 e2 = v2 - v0;
  ng = cross(e1, e2);
  const vec3 p = cross(d, e2);
  const float det = dot(e1, p);
  if (det == 0.0) return false;
  const float invDet = 1.0 / det;
  const vec3 s = o - v0;
  u = dot(s, p) * invDet;
  if (u < 0.0 || u > 1.0) return false;
  const vec3 q = cross(s, e1);
  v = dot(d, q) * invDet;
  if (v < 0.0 || u + v > 1.0) return false;
  th = dot(e2, q) * invDet;
  return th >= tnear && th <= tfar;
}

// a + (b - a) f, as math.h's lerp (and positionAt between time steps) computes it.
vec3 lerp3(vec3 a, vec3 b, float f) {
  precise const vec3 r = a + (b - a) * f;  // unfused, as the CPU computes it
  return r;
}

vec3 floats3(Floats f, uint at) { return vec3(f.v[at], f.v[at + 1u], f.v[at + 2u]); }

// Vertex k of triangle `at` (its first float) of a triangle array.
vec3 cornerOf(Floats f, uint at, uint k) { return floats3(f, at + 3u * k); }

// Where the time steps around traceTau begin for an object of `steps` steps, and how far
// between that step and the next the ray's time lies (FrameScene's lerpSteps).
uint stepAt(uint steps, out float frac) {
  const float x = clamp(traceTau, 0.0, 1.0) * float(steps - 1u);
  const uint i = min(uint(x), steps - 2u);
  frac = x - float(i);
  return i;
}

// Entry distance into node n's box within [tnear, tfar], or -1 when the ray misses it (an empty
// box, lo > hi, is always missed).
float enterBox(BvhNode n, vec3 o, vec3 inv, float tnear, float tfar) {
  if (n.lox > n.hix) return -1.0;
  const vec3 t0 = (vec3(n.lox, n.loy, n.loz) - o) * inv;
  const vec3 t1 = (vec3(n.hix, n.hiy, n.hiz) - o) * inv;
  const vec3 lo = min(t0, t1), hi = max(t0, t1);
  const float t = max(max(lo.x, lo.y), max(lo.z, tnear));
  const float u = min(min(hi.x, hi.y), min(hi.z, tfar));
  return t <= u ? t : -1.0;
}

// The nearest accepted hit in [tnear, tfar] (TRACE_ANY: the first found; TRACE_ALL: none is
// kept, unless the filter stops the ray). Returns whether there is one.
bool traverse(vec3 o, vec3 d, float tnear, float tfar, uint flags, out TraceHit hit) {
  // Zero components become huge: the slabs stay correct for axis-parallel rays.
  const vec3 inv = vec3(1.0) / mix(d, vec3(1e-30), equal(d, vec3(0.0)));
  Nodes nodes = Nodes(bvh.nodes);
  Floats tris = Floats(bvh.triangles);
  Uints roots = Uints(bvh.objectRoot);
  Uints prims = Uints(bvh.trianglePrim);
  hit = TraceHit(0.0, 0.0, 0.0, -1, -1);
  float best = tfar;
  uint top[64], bottom[64];
  int topSize = 0;
  top[topSize++] = bvh.topRoot;
  while (topSize > 0) {
    const BvhNode n = nodes.n[top[--topSize]];
    if (enterBox(n, o, inv, tnear, best) < 0.0) continue;
    if (n.count == 0u) {
      top[topSize++] = n.a;
      top[topSize++] = n.a + 1u;
      continue;
    }
    for (uint k = 0u; k < n.count; ++k) {
      const uint object = roots.v[n.a + k];
      // A moving object's triangle at the ray's time: the two steps around it, interpolated.
      const uvec4 motion = uvec4(Uints(bvh.objectMotion).v[4u * object],
                                 Uints(bvh.objectMotion).v[4u * object + 1u],
                                 Uints(bvh.objectMotion).v[4u * object + 2u], 0u);
      float frac = 0.0;
      const uint step = motion.x >= 2u ? stepAt(motion.x, frac) : 0u;
      int size = 0;
      bottom[size++] = roots.v[object];
      while (size > 0) {
        const BvhNode m = nodes.n[bottom[--size]];
        if (enterBox(m, o, inv, tnear, best) < 0.0) continue;
        if (m.count == 0u) {
          bottom[size++] = m.a;
          bottom[size++] = m.a + 1u;
          continue;
        }
        for (uint t = m.a; t < m.a + m.count; ++t) {
          float th, u, v;
          vec3 ng, v0, v1, v2;
          if (motion.x >= 2u) {
            Floats steps = Floats(bvh.motionTriangles);
            const uint at = 9u * (motion.z + (t - motion.y) * motion.x + step);
            v0 = lerp3(cornerOf(steps, at, 0u), cornerOf(steps, at + 9u, 0u), frac);
            v1 = lerp3(cornerOf(steps, at, 1u), cornerOf(steps, at + 9u, 1u), frac);
            v2 = lerp3(cornerOf(steps, at, 2u), cornerOf(steps, at + 9u, 2u), frac);
          } else {
            v0 = cornerOf(tris, 9u * t, 0u);
            v1 = cornerOf(tris, 9u * t, 1u);
            v2 = cornerOf(tris, 9u * t, 2u);
          }
          if (!hitTriangle(v0, v1, v2, o, d, tnear, best, th, u, v, ng)) continue;
          const int prim = int(prims.v[t]);
          if ((flags & TRACE_FILTERED) != 0u) {
            const int f = hitFilter(flags, int(object), prim, th, u, v, ng, o, d);
            if (f == HIT_IGNORE) continue;
            if (f == HIT_STOP) {
              hit = TraceHit(th, u, v, int(object), prim);
              return true;
            }
          }
          if ((flags & TRACE_ALL) != 0u) continue;
          hit = TraceHit(th, u, v, int(object), prim);
          if ((flags & TRACE_ANY) != 0u) return true;
          best = th;
        }
      }
    }
  }
  return hit.object >= 0;
}
