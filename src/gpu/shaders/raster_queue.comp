#version 460
// raster_queue: the large triangles raster_triangles queued, a workgroup of 8x8 threads a
// triangle stepping over its pixel box 8x8 pixels at a time (a persistent loop: the queue's
// length is known only on the device).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "raster_args.h"
#include "scene_data.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { uint64_t args; };

#include "camera.glsl"
#include "scene.glsl"
#include "raster.glsl"

void main() {
  const RasterArgs a = RasterArgsRef(args).a;
  useScene(a.scene);
  traceTau = a.tau;
  RasterQueue q = RasterQueue(a.queue);
  const uint n = min(q.count, a.queueCapacity);
  const int lx = int(gl_LocalInvocationID.x), ly = int(gl_LocalInvocationID.y);
  for (uint i = gl_WorkGroupID.x; i < n; i += gl_NumWorkGroups.x) {
    const RasterTriangle t = q.t[i];
    if (a.sampleIds != 0ul) {  // sample mode: 8 x 8 cells at a time
      const ivec4 c = cellBox(t, a);
      for (int by = c.y; by <= c.w; by += 8)
        for (int bx = c.x; bx <= c.z; bx += 8) {
          const int cx = bx + lx, cy = by + ly;
          if (cx <= c.z && cy <= c.w) drawCell(t, a, cx, cy);
        }
      continue;
    }
    for (int by = t.py0; by <= t.py1; by += 8)
      for (int bx = t.px0; bx <= t.px1; bx += 8) {
        const int px = bx + lx, py = by + ly;
        if (px <= t.px1 && py <= t.py1) drawPixel(t, a, px, py);
      }
  }
}
