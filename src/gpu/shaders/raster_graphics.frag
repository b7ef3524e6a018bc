#version 460
// The graphics pipeline's visibility draw, fragment stage: the triangle's index + 1 into the
// colour attachment (the depth test keeping the nearest), alpha-masked texels discarded along the
// pixel centre's camera ray as the compute rasterizer tests them (Rasterizer::alphaKeeps).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "camera_data.h"
#include "raster_graphics_args.h"
#include "scene_data.h"

layout(push_constant, scalar) uniform Push { RasterDrawArgs a; };
layout(location = 0) flat in uint triangle;
layout(location = 0) out uint id;

#include "camera.glsl"
#include "scene.glsl"

void main() {
  useScene(a.scene);
  traceTau = a.tau;
  const GpuObject ob = Objects(S.objects).o[a.object];
  const GpuMaterial m = Materials(S.materials).m[ob.material];
  if ((m.flags & TD_MAT_ALPHA_MASK) != 0u) {
    const int prim = int(triangle - ob.firstIndex / 3u);
    const uvec3 k = triangleVertices(ob, prim);
    vec3 o, d;
    float tnear, th, u, v;
    cameraRay(CameraRef(a.camera).c, int(gl_FragCoord.x), int(gl_FragCoord.y), o, d, tnear);
    intersectTriangle(o, d, vertexPositionAt(ob, k.x), vertexPositionAt(ob, k.y),
                      vertexPositionAt(ob, k.z), th, u, v);
    if (surfaceAlpha(int(a.object), prim, u, v) < m.alphaCutoff) discard;
  }
  id = triangle + 1u;
}
