#version 460
// deferred_shading on the GPU, pixel for pixel what DeferredShadingPass::execute computes:
// Listing 5 over the G-buffer, the eye direction from the camera to the point; the sky along the
// camera ray where the G-buffer holds background. With shadow maps (a.shadowMaps != 0): L - (1 - S),
// S from the maps deciding every light (shadow_term.glsl), as ss_fallback and blend make it.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "gbuffer_args.h"
#include "scene_data.h"
#include "shadow_maps_data.h"
#include "whitted_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { GBufferShadeArgs a; };

#include "camera.glsl"
#include "scene.glsl"
#include "gbuffer.glsl"
#include "shadow_maps.glsl"
#include "whitted.glsl"
#include "shadow_term.glsl"

void main() {
  const GpuView view = ViewRef(a.view).v;
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= view.camera.width || y >= view.camera.height) return;
  useScene(a.scene);
  const GBufferTargets g = TargetsRef(a.targets).g;
  const uint pixel = uint(y + a.viewY) * uint(a.frameWidth) + uint(x + a.viewX);
  Surface s;
  vec3 color;
  if (!readSurface(g, pixel, s)) {
    vec3 origin, dir;
    float tnear;
    cameraRay(view.camera, x, y, origin, dir, tnear);
    color = skyRadiance(dir);
  } else {
    const vec3 eye = vec3(view.camera.eye[0], view.camera.eye[1], view.camera.eye[2]);
    const vec3 forward = vec3(view.camera.forward[0], view.camera.forward[1], view.camera.forward[2]);
    const vec3 wo = view.perspective != 0 ? safeNormalize(eye - s.position) : -forward;
    color = shadeUnshadowed(s, wo);
    if (a.shadowMaps != 0ul) {
      useShadowMaps(a.shadowMaps);
      whitted = WhittedConfig(0, 0.0, a.shadowCull, TD_WHITTED_MAPS);
      vec3 shares;
      color = color - (vec3(1.0) - shadowTermOf(s, wo, color, -1, shares));  // lights summed once
    }
  }
  put3(a.hdr, pixel, color);
}
