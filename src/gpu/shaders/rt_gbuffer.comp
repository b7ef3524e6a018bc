#version 460
// rt_gbuffer on the GPU, pixel for pixel what RTGBufferPass::execute writes: the camera ray (back
// faces of single-sided materials culled), the surface resolved at the pixel cone's texture
// level, its depth and motion; the background cleared.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "gbuffer_args.h"
#include "scene_data.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { GBufferArgs a; };

#include "camera.glsl"
#include "scene.glsl"
#include "gbuffer.glsl"

void main() {
  const GpuView view = ViewRef(a.view).v;
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= view.camera.width || y >= view.camera.height) return;
  useScene(a.scene);
  const GBufferTargets g = TargetsRef(a.targets).g;
  const uint pixel = uint(y + a.viewY) * uint(a.frameWidth) + uint(x + a.viewX);
  vec3 origin, dir;
  float tnear;
  cameraRay(view.camera, x, y, origin, dir, tnear);
  TraceHit h;
  if (!traverse(origin, dir, tnear, 1e30, TRACE_FILTERED | TRACE_CULL_BACK, h)) {
    writeBackground(g, pixel, g.motion != 0ul ? backgroundMotion(view, dir) : vec2(0.0));
    return;
  }
  const Surface s =
      resolveSurface(h.object, h.prim, origin, dir, h.t, h.u, h.v, view.camera.pixelSpread);
  const float depth = g.depth != 0ul ? depthOf(view, origin + dir * h.t) : 0.0;
  writeSurface(g, pixel, s, depth,
               g.motion != 0ul ? motionVector(view, a.motion, s.object, s.position) : vec2(0.0));
}
