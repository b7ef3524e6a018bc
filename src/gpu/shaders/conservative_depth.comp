#version 460
// conservative_depth: a face's conservative shadow map (raster/conservative_depth.cpp) operation for
// operation: each triangle clipped to the front of the near plane, projected, and every texel its
// area touches (not only those whose centre it covers) given the nearest depth its plane reaches
// there, never nearer than its nearest corner; the nearest over all triangles kept by atomicMax.
// In the set-up phase a thread draws a triangle whose texel box is small and queues a large one in
// bands of rows; in the queue phase a workgroup draws each queued band 8x8 texels at a time.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "raster_args.h"
#include "scene_data.h"
#include "shadow_map_draw_args.h"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { uint64_t args; };

#include "scene.glsl"
#include "spans.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ArgsRef {
  ConservativeArgs a;
};
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer NearKeys { uint64_t v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer WorldTriangles {
  ConservativeWorldTriangle t[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Queue {
  uint count, pad0, pad1, pad2;
  ConservativeTriangle t[];
};

const int kDirectTexels = 128;  // a box up to this many texels is drawn by its set-up thread
const int kBandRows = 32;       // a queued triangle's rows per workgroup

ConservativeArgs A;

// Projector::viewZ and ::project.
float viewZ(vec3 p) {
  precise const vec3 r = p - v3(A.eye);
  precise const float z = r.x * A.forward[0] + r.y * A.forward[1] + r.z * A.forward[2];
  return z;
}
vec3 project(vec3 p) {
  const float m[16] = A.viewProj;
  precise float w = 1.0;
  if (A.perspective != 0) w = m[12] * p.x + m[13] * p.y + m[14] * p.z + m[15];
  precise const float x = (m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3]) / w;
  precise const float y = (m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7]) / w;
  const float z = viewZ(p);
  precise float d;
  if (A.perspective != 0)
    d = A.nearPlane / z;
  else
    d = (A.farPlane - z) / (A.farPlane - A.nearPlane);
  precise const float sx = (x * 0.5 + 0.5) * float(A.width);
  precise const float sy = (0.5 - y * 0.5) * float(A.height);
  return vec3(sx, sy, d);
}

// drawTriangle's set-up: edge functions (inside >= 0), the depth plane, the longest edge.
struct Setup {
  float ea[3], eb[3], ec[3];
  float pa, pb, pc, dMax, reach;
  int longest;
  bool edgeOn;
};

Setup setUp(vec3 a, vec3 b, vec3 c) {
  Setup s;
  s.dMax = max(max(a.z, b.z), c.z);
  precise const float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  const vec3 v[3] = vec3[](a, b, c);
  const float sign = area >= 0.0 ? 1.0 : -1.0;
  for (int e = 0; e < 3; ++e) {
    const vec3 p = v[e], q = v[(e + 1) % 3];
    precise const float ea = sign * (p.y - q.y), eb = sign * (q.x - p.x);
    precise const float ec = sign * (p.x * q.y - p.y * q.x);
    s.ea[e] = ea, s.eb[e] = eb, s.ec[e] = ec;
  }
  s.edgeOn = abs(area) < 1e-6;  // seen edge-on: a segment, covered where it passes
  s.pa = 0.0, s.pb = 0.0, s.pc = s.dMax;
  if (!s.edgeOn) {
    precise const float pa = ((b.z - a.z) * (c.y - a.y) - (c.z - a.z) * (b.y - a.y)) / area;
    precise const float pb = ((c.z - a.z) * (b.x - a.x) - (b.z - a.z) * (c.x - a.x)) / area;
    precise const float pc = a.z - pa * a.x - pb * a.y;
    s.pa = pa, s.pb = pb, s.pc = pc;
  }
  precise const float reach = 0.5 * (abs(s.pa) + abs(s.pb));
  s.reach = reach;
  s.longest = 0;
  for (int e = 1; e < 3; ++e) {
    precise const float le = s.ea[e] * s.ea[e] + s.eb[e] * s.eb[e];
    precise const float ll = s.ea[s.longest] * s.ea[s.longest] + s.eb[s.longest] * s.eb[s.longest];
    if (le > ll) s.longest = e;
  }
  return s;
}

void drawTexel(Setup s, uint object, int x, int y) {
  const float cx = float(x) + 0.5, cy = float(y) + 0.5;
  bool touches = true;
  if (s.edgeOn) {
    const int e = s.longest;
    precise const float slack = 0.5 * (abs(s.ea[e]) + abs(s.eb[e])) * 1.001 + 1e-6;
    precise const float f = s.ea[e] * cx + s.eb[e] * cy + s.ec[e];
    touches = abs(f) <= slack;
  } else {
    for (int e = 0; e < 3 && touches; ++e) {
      precise const float slack = 0.5 * (abs(s.ea[e]) + abs(s.eb[e])) * 1.001 + 1e-6;
      precise const float f = s.ea[e] * cx + s.eb[e] * cy + s.ec[e] + slack;
      touches = f >= 0.0;
    }
  }
  if (!touches) return;
  precise const float plane = s.pa * cx + s.pb * cy + s.pc + s.reach;
  const float d = s.edgeOn ? s.dMax : min(s.dMax, plane);
  if (!(d > 0.0)) return;  // the map starts at depth 0 (and NaN draws nothing)
  const uint64_t key = (uint64_t(floatBitsToUint(d)) << 32) | uint64_t(~object);
  NearKeys near = NearKeys(A.near);
  const uint i = uint(y) * uint(A.width) + uint(x);
  if (near.v[i] >= key) return;  // a plain read first: a texel already nearer needs no atomic
  atomicMax(near.v[i], key);
}

// drawTriangle: small boxes here, large ones to the queue.
void drawProjected(vec3 a, vec3 b, vec3 c, uint object) {
  const float lo = min(min(a.x, b.x), c.x), hi = max(max(a.x, b.x), c.x);
  const float bot = min(min(a.y, b.y), c.y), top = max(max(a.y, b.y), c.y);
  if (!(hi >= 0.0 && top >= 0.0 && lo < float(A.width) && bot < float(A.height))) return;
  // Clamped as floats first: a corner projected far off the map stays in range.
  const int x0 = int(max(floor(lo), 0.0)), x1 = int(min(floor(hi), float(A.width - 1)));
  const int y0 = int(max(floor(bot), 0.0)), y1 = int(min(floor(top), float(A.height - 1)));
  int first = y0;  // the rows from here on are drawn by this thread
  if ((x1 - x0 + 1) * (y1 - y0 + 1) > kDirectTexels) {
    // Queued in bands of kBandRows rows, each drawn by a workgroup of its own: a large triangle
    // spreads over many workgroups, and no loop runs long (lavapipe ends a loop after 65535
    // iterations, counted over a workgroup's whole run).
    Queue q = Queue(A.queue);
    const int bands = (y1 - y0) / kBandRows + 1;
    const uint slot = atomicAdd(q.count, uint(bands));
    ConservativeTriangle t;
    t.a = float[](a.x, a.y, a.z), t.b = float[](b.x, b.y, b.z), t.c = float[](c.x, c.y, c.z);
    t.object = object;
    t.x0 = x0, t.x1 = x1;
    for (int k = 0; k < bands && slot + uint(k) < A.queueCapacity; ++k) {
      t.y0 = y0 + kBandRows * k, t.y1 = min(t.y0 + kBandRows - 1, y1);
      q.t[slot + uint(k)] = t;
      first = t.y1 + 1;
    }
    if (first > y1) return;  // (a full queue leaves the rest here)
  }
  const Setup s = setUp(a, b, c);
  for (int y = first; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) drawTexel(s, object, x, y);
}

// drawWorldTriangle: clipped to the front of the near plane when the face is a perspective one.
void drawWorld(vec3 a, vec3 b, vec3 c, uint object) {
  if (A.perspective == 0) {
    drawProjected(project(a), project(b), project(c), object);
    return;
  }
  const vec3 v[3] = vec3[](a, b, c);
  float z[3];
  int front = 0;
  for (int k = 0; k < 3; ++k) {
    precise const float zk = viewZ(v[k]) - A.nearPlane;
    z[k] = zk;
    front += zk > 0.0 ? 1 : 0;
  }
  if (front == 0) return;
  if (front == 3) {
    drawProjected(project(a), project(b), project(c), object);
    return;
  }
  vec3 poly[4];
  int n = 0;
  precise const float nudge = 1e-4 * A.nearPlane;  // just in front of the plane
  for (int k = 0; k < 3; ++k) {
    const int j = (k + 1) % 3;
    if (z[k] > 0.0) poly[n++] = v[k];
    if ((z[k] > 0.0) != (z[j] > 0.0)) {
      precise const float t = z[k] / (z[k] - z[j]);
      precise const vec3 on = v[k] + (v[j] - v[k]) * clamp(t, 0.0, 1.0);
      precise const vec3 p = on + v3(A.forward) * nudge;
      poly[n++] = p;
    }
  }
  vec3 s[4];
  for (int k = 0; k < n; ++k) s[k] = project(poly[k]);
  for (int k = 1; k + 1 < n; ++k) drawProjected(s[0], s[k], s[k + 1], object);
}

void setUpTriangle(uint i) {
  if (i >= A.triangles) {
    const ConservativeWorldTriangle t = WorldTriangles(A.boxes).t[i - A.triangles];
    drawWorld(v3(t.a), v3(t.b), v3(t.c), t.object);
    return;
  }
  int object;
  const uint triangle = spanTriangle(A.spans, A.spanCount, i, object);
  const GpuObject ob = Objects(S.objects).o[object];
  const uvec3 k = triangleVertices(ob, int(triangle - ob.firstIndex / 3u));
  drawWorld(vertexPosition(k.x), vertexPosition(k.y), vertexPosition(k.z), uint(object));
}

void drawQueued() {
  Queue q = Queue(A.queue);
  const uint n = min(q.count, A.queueCapacity);
  const int lx = int(gl_LocalInvocationIndex % 8u), ly = int(gl_LocalInvocationIndex / 8u);
  for (uint i = gl_WorkGroupID.x; i < n; i += gl_NumWorkGroups.x) {
    const ConservativeTriangle t = q.t[i];
    const Setup s = setUp(v3(t.a), v3(t.b), v3(t.c));
    for (int by = t.y0; by <= t.y1; by += 8)
      for (int bx = t.x0; bx <= t.x1; bx += 8) {
        const int x = bx + lx, y = by + ly;
        if (x <= t.x1 && y <= t.y1) drawTexel(s, t.object, x, y);
      }
  }
}

void main() {
  A = ArgsRef(args).a;
  useScene(A.scene);
  if (A.phase == TD_CONSERVATIVE_QUEUE) {
    drawQueued();
    return;
  }
  const uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  const uint i = group * 64u + gl_LocalInvocationIndex;
  if (i < A.triangles + A.boxTriangles) setUpTriangle(i);
}
