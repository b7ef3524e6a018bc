#version 460
// raster_resolve: one view's visibility buffer resolved pixel by pixel as VisibleSurfaces and
// GBufferWriter resolve it (passes/common/gbuffer_writer.h): the visible triangle intersected by
// the pixel's camera ray, the surface at the pixel cone's texture level, the rasterizer's depth,
// motion from the pixel centre; the background cleared. Into the G-buffer targets that are
// non-zero (raster_gbuffer: all) and, when `hdr` is, shaded there as vbuffer_shading shades it
// (Listing 5, no shadows; the sky along the camera ray). A reflection probe's faces are resolved
// and shaded the same way (ReflectionProbes::draw).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "gbuffer_args.h"
#include "raster_args.h"
#include "scene_data.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { RasterResolveArgs a; };

#include "camera.glsl"
#include "scene.glsl"
#include "gbuffer.glsl"
#include "raster.glsl"

void main() {
  const GpuView view = ViewRef(a.view).v;
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= view.camera.width || y >= view.camera.height) return;
  useScene(a.scene);
  GBufferTargets g;
  if (a.targets != 0ul)
    g = TargetsRef(a.targets).g;
  else
    g = GBufferTargets(0ul, 0ul, 0ul, 0ul, 0ul, 0ul, 0ul, 0ul, 0ul, 0ul, 0ul, 0ul);
  const uint pixel = uint(y + a.viewY) * uint(a.frameWidth) + uint(x + a.viewX);
  const uint64_t key = Visibility(a.visibility).v[uint(y) * uint(view.camera.width) + uint(x)];
  vec3 origin, dir;
  float tnear;
  cameraRay(view.camera, x, y, origin, dir, tnear);
  if (key == 0ul) {
    writeBackground(g, pixel, g.motion != 0ul ? backgroundMotion(view, dir) : vec2(0.0));
    if (a.hdr != 0ul) put3(a.hdr, pixel, skyRadiance(dir));
    return;
  }
  const uint triangle = ~uint(key & 0xfffffffful);
  const int object = objectOfTriangle(triangle, a.objectCount);
  const GpuObject ob = Objects(S.objects).o[object];
  const int prim = int(triangle - ob.firstIndex / 3u);
  const uvec3 k = triangleVertices(ob, prim);
  float t, u, v;
  intersectTriangle(origin, dir, vertexPosition(k.x), vertexPosition(k.y), vertexPosition(k.z), t,
                    u, v);
  const Surface s = resolveSurface(object, prim, origin, dir, t, u, v, view.camera.pixelSpread);
  const float depth = uintBitsToFloat(uint(key >> 32));
  writeSurface(g, pixel, s, depth,
               g.motion != 0ul
                   ? motionAtPixel(view, a.motion, s.object, s.position, vec2(x, y) + 0.5)
                   : vec2(0.0));
  if (a.hdr != 0ul) {
    const vec3 eye = vec3(view.camera.eye[0], view.camera.eye[1], view.camera.eye[2]);
    const vec3 forward =
        vec3(view.camera.forward[0], view.camera.forward[1], view.camera.forward[2]);
    const vec3 wo = a.probe != 0          ? -dir
                    : view.perspective != 0 ? safeNormalize(eye - s.position)
                                            : -forward;
    put3(a.hdr, pixel, shadeUnshadowed(s, wo));
  }
}
