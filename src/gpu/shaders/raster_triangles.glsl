// The compute rasterizer's set-up, one thread a triangle, operation for operation
// Rasterizer::prepare (raster/rasterizer.cpp): clip-space vertices, outcodes, Sutherland-Hodgman
// against the planes a triangle crosses (near, far and the guard band), the fan in 8-bit
// fixed point, back faces culled, the depth plane from the unsnapped positions (in double, as
// the CPU, unless TD_SETUP_FLOAT: a device without 64-bit floats), the pixel box. A small box is
// drawn here; a large one goes to the queue that raster_queue.comp draws a workgroup a triangle.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#ifndef TD_SETUP_FLOAT
#extension GL_EXT_shader_explicit_arithmetic_types_float64 : require
#define SETUP_REAL double
#else
#define SETUP_REAL float
#endif
#include "bvh.h"
#include "raster_args.h"
#include "scene_data.h"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { uint64_t args; };

#include "camera.glsl"
#include "scene.glsl"
#include "spans.glsl"
#include "raster.glsl"

const float kGuardBand = 4.0;
const int kDirectPixels = 128;  // a box up to this many pixels is drawn by its set-up thread
const int kBandRows = 32;       // a queued triangle's pixel rows per queue entry

shared uint groupCounts[TD_RASTER_COUNT_N];

float planeDist(vec4 v, int plane) {
  switch (plane) {
    case 0: return v.w - v.z;  // near: z/w <= 1 in reversed Z
    case 1: return v.z;        // far: z >= 0
    case 2: return v.x + kGuardBand * v.w;
    case 3: return kGuardBand * v.w - v.x;
    case 4: return v.y + kGuardBand * v.w;
    default: return kGuardBand * v.w - v.y;
  }
}

uint outcode(vec4 v) {
  uint code = 0u;
  for (int p = 0; p < 6; ++p)
    if (!(planeDist(v, p) >= 0.0)) code |= 1u << p;
  return code;
}

// Row-major vp times (p, 1), summed in the CPU's order.
vec4 toClip(float m[16], vec3 p) {
  precise vec4 c;
  c.x = m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3];
  c.y = m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7];
  c.z = m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11];
  c.w = m[12] * p.x + m[13] * p.y + m[14] * p.z + m[15];
  return c;
}

int toFixed(float v) {
  precise const float f = v * 256.0;
  return int(f + (f >= 0.0 ? 0.5 : -0.5));
}

bool anywhere = false;  // sample mode (RasterArgs::sampleIds)

// The clipped polygon (at most 9 corners) and its corners on the screen.
vec4 poly[12];
int X[12], Y[12];
float Z[12], SX[12], SY[12];

void project(int k, vec4 v, int W, int H) {
  precise const float iw = 1.0 / v.w;
  precise const float sx = (v.x * iw * 0.5 + 0.5) * float(W);
  precise const float sy = (0.5 - v.y * iw * 0.5) * float(H);
  SX[k] = sx;
  SY[k] = sy;
  X[k] = toFixed(sx);
  Y[k] = toFixed(sy);
  Z[k] = v.z * iw;
}

int clipPolygon(int n, uint mask) {
  vec4 tmp[12];
  for (int plane = 0; plane < 6 && n > 0; ++plane) {
    if ((mask & (1u << plane)) == 0u) continue;
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const vec4 a = poly[i], b = poly[i + 1 == n ? 0 : i + 1];
      const float da = planeDist(a, plane), db = planeDist(b, plane);
      if (da >= 0.0) tmp[m++] = a;
      if ((da >= 0.0) != (db >= 0.0)) {
        precise const float t = da / (da - db);
        precise const vec4 c = a + (b - a) * t;
        tmp[m++] = c;
      }
    }
    n = m;
    for (int i = 0; i < n; ++i) poly[i] = tmp[i];
  }
  return n;
}

// setUpPiece: false when the piece covers no pixel centre or is degenerate.
bool setUpPiece(int a, int b, int c, int W, int H, out RasterTriangle t) {
  t.x[0] = X[a], t.x[1] = X[b], t.x[2] = X[c];
  t.y[0] = Y[a], t.y[1] = Y[b], t.y[2] = Y[c];
  // As the CPU: the screen differences in float, the plane's solution in double.
  const SETUP_REAL ux = SX[b] - SX[a], uy = SY[b] - SY[a], vx = SX[c] - SX[a], vy = SY[c] - SY[a];
  const SETUP_REAL uz = SETUP_REAL(Z[b]) - Z[a], vz = SETUP_REAL(Z[c]) - Z[a];
  precise const SETUP_REAL det = ux * vy - uy * vx;
  if (det == 0.0) return false;
  precise const SETUP_REAL dzdx = (uz * vy - vz * uy) / det;
  precise const SETUP_REAL dzdy = (vz * ux - uz * vx) / det;
  t.dzdx = float(dzdx);
  t.dzdy = float(dzdy);
  t.zRef = Z[a];
  t.xRef = SX[a];
  t.yRef = SY[a];
  const int minX = min(t.x[0], min(t.x[1], t.x[2])), maxX = max(t.x[0], max(t.x[1], t.x[2]));
  const int minY = min(t.y[0], min(t.y[1], t.y[2])), maxY = max(t.y[0], max(t.y[1], t.y[2]));
  if (anywhere) {  // sample mode: the pixels the box touches (samples lie anywhere in them)
    t.px0 = max(0, minX >> 8);
    t.px1 = min(W - 1, maxX >> 8);
    t.py0 = max(0, minY >> 8);
    t.py1 = min(H - 1, maxY >> 8);
  } else {
    t.px0 = max(0, (minX - 128 + 255) >> 8);
    t.px1 = min(W - 1, (maxX - 128) >> 8);
    t.py0 = max(0, (minY - 128 + 255) >> 8);
    t.py1 = min(H - 1, (maxY - 128) >> 8);
  }
  return t.px0 <= t.px1 && t.py0 <= t.py1;
}

// The work of drawing a box: its pixels, or in sample mode its cells.
int boxSize(RasterTriangle t, RasterArgs a) {
  if (!anywhere) return (t.px1 - t.px0 + 1) * (t.py1 - t.py0 + 1);
  const ivec4 c = cellBox(t, a);
  return (c.z - c.x + 1) * (c.w - c.y + 1);
}

void drawBox(RasterTriangle t, RasterArgs a) {
  if (anywhere) {
    const ivec4 c = cellBox(t, a);
    for (int cy = c.y; cy <= c.w; ++cy)
      for (int cx = c.x; cx <= c.z; ++cx) drawCell(t, a, cx, cy);
    return;
  }
  for (int py = t.py0; py <= t.py1; ++py)
    for (int px = t.px0; px <= t.px1; ++px) drawPixel(t, a, px, py);
}

void rasterize(uint triangle, int object, RasterArgs a) {
  const GpuObject ob = Objects(S.objects).o[object];
  const GpuMaterial m = Materials(S.materials).m[ob.material];
  const int prim = int(triangle - ob.firstIndex / 3u);
  const uvec3 k = triangleVertices(ob, prim);
  const vec4 c0 = toClip(a.viewProj, vertexPositionAt(ob, k.x));
  const vec4 c1 = toClip(a.viewProj, vertexPositionAt(ob, k.y));
  const vec4 c2 = toClip(a.viewProj, vertexPositionAt(ob, k.z));
  const uint o0 = outcode(c0), o1 = outcode(c1), o2 = outcode(c2);
  if ((o0 & o1 & o2) != 0u) {
    atomicAdd(groupCounts[TD_RASTER_CULLED], 1u);
    return;
  }
  const int W = a.camera.width, H = a.camera.height;
  int n = 3;
  poly[0] = c0, poly[1] = c1, poly[2] = c2;
  if ((o0 | o1 | o2) != 0u) {
    n = clipPolygon(3, o0 | o1 | o2);
    atomicAdd(groupCounts[TD_RASTER_CLIPPED], 1u);
  }
  if (n < 3) return;
  for (int i = 0; i < n; ++i) project(i, poly[i], W, H);
  const bool bothFaces = (m.flags & TD_MAT_DOUBLE_SIDED) != 0u || a.bothFaces != 0u;
  for (int i = 1; i + 1 < n; ++i) {
    int pa = 0, pb = i, pc = i + 1;
    const int64_t area = int64_t(X[pb] - X[pa]) * int64_t(Y[pc] - Y[pa]) -
                         int64_t(Y[pb] - Y[pa]) * int64_t(X[pc] - X[pa]);
    if (area == 0) continue;
    // Counter-clockwise in the world is clockwise on a y-down screen: area < 0 is front.
    if (area > 0) {
      if (!bothFaces) {
        atomicAdd(groupCounts[TD_RASTER_CULLED], 1u);
        continue;
      }
    } else {
      pb = i + 1;
      pc = i;
    }
    RasterTriangle t;
    if (!setUpPiece(pa, pb, pc, W, H, t)) continue;
    t.triangle = triangle;
    t.alphaMask = (m.flags & TD_MAT_ALPHA_MASK) != 0u ? 1u : 0u;
    t.pad = 0u;
    atomicAdd(groupCounts[TD_RASTER_BINNED], 1u);
    if (boxSize(t, a) > kDirectPixels) {
      // Queued in bands of kBandRows pixel rows, each drawn by a workgroup: a large triangle
      // spreads over many workgroups, and no workgroup's loop runs long (lavapipe ends a loop
      // after 65535 iterations, counted over a workgroup's whole run: a 4K frame's ceiling lost
      // its lower rows). Sample mode takes each band's cells (a cell row two bands share is
      // tested by both: a depth test twice gives the same key).
      RasterQueue q = RasterQueue(a.queue);
      const int y0 = t.py0, y1 = t.py1;
      const int bands = (y1 - y0) / kBandRows + 1;
      const uint slot = atomicAdd(q.count, uint(bands));
      int first = y0;  // the rows from here on are drawn by this thread
      for (int k = 0; k < bands && slot + uint(k) < a.queueCapacity; ++k) {
        t.py0 = y0 + kBandRows * k, t.py1 = min(t.py0 + kBandRows - 1, y1);
        q.t[slot + uint(k)] = t;
        first = t.py1 + 1;
      }
      if (first > y0) atomicAdd(groupCounts[TD_RASTER_QUEUED], 1u);
      if (first > y1) continue;
      t.py0 = first, t.py1 = y1;  // (a full queue leaves the rest here)
    }
    drawBox(t, a);  // small, or the rest of a full queue's
  }
}

void main() {
  if (gl_LocalInvocationIndex < TD_RASTER_COUNT_N) groupCounts[gl_LocalInvocationIndex] = 0u;
  barrier();
  const RasterArgs a = RasterArgsRef(args).a;
  useScene(a.scene);
  traceTau = a.tau;
  anywhere = a.sampleIds != 0ul;
  const uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  const uint i = group * 64u + gl_LocalInvocationIndex;
  if (i < a.triangles) {
    int object;
    const uint triangle = spanTriangle(a.spans, a.spanCount, i, object);
    rasterize(triangle, object, a);
  }
  barrier();
  if (gl_LocalInvocationIndex < TD_RASTER_COUNT_N && groupCounts[gl_LocalInvocationIndex] != 0u)
    atomicAdd(RasterCounters(a.counters).c[gl_LocalInvocationIndex],
              groupCounts[gl_LocalInvocationIndex]);
}
