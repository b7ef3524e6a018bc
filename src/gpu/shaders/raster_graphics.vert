#version 460
// The graphics pipeline's visibility draw, vertex stage: vertex gl_VertexIndex of the object's
// triangle list pulled from the scene (where it is at the draw's shutter fraction) and projected by
// the jittered camera, y turned down for Vulkan's framebuffer; the triangle's index over all
// objects handed on flat.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "camera_data.h"
#include "raster_graphics_args.h"
#include "scene_data.h"

layout(push_constant, scalar) uniform Push { RasterDrawArgs a; };
layout(location = 0) flat out uint triangle;

#include "scene.glsl"

void main() {
  useScene(a.scene);
  traceTau = a.tau;
  const GpuObject ob = Objects(S.objects).o[a.object];
  const int prim = gl_VertexIndex / 3;
  const uvec3 k = triangleVertices(ob, prim);
  const int corner = gl_VertexIndex - 3 * prim;
  const vec3 p = vertexPositionAt(ob, corner == 0 ? k.x : (corner == 1 ? k.y : k.z));
  const float m[16] = a.viewProj;
  const vec4 c = vec4(m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3],
                      m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
                      m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11],
                      m[12] * p.x + m[13] * p.y + m[14] * p.z + m[15]);
  gl_Position = vec4(c.x, -c.y, c.z, c.w);
  triangle = ob.firstIndex / 3u + uint(prim);
}
