#version 460
// rt_dof on the GPU, one invocation a mask pixel, what RTDofPass::execute computes: the pixel's
// x_f lens rays (the same Sobol samples for the jitter and the aperture point), each from the
// near plane with back faces culled, shaded as rt-only shades (whitted.glsl: shadows, mirrors,
// glass) or, with reuse_raster, given the sharp image's colour where it shows the hit; each ray's
// colour and CoC split into the near and far field by dof::nearShare, in the CPU's order.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "rt_dof_args.h"
#include "scene_data.h"
#include "shadow_maps_data.h"
#include "whitted_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { uint64_t args; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ArgsRef {
  RtDofArgs a;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Views {
  RtDofView v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Out { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Counts { uint v[]; };

RtDofArgs A;

#include "camera.glsl"
#include "scene.glsl"
#include "shadow_maps.glsl"
#include "whitted.glsl"
#include "sobol.glsl"
#include "thin_lens.glsl"

const float kZoneOfFocusCoc = 1.41421356;

// ThinLens::coc.
float cocOf(float z) {
  precise const float c = A.lensK * (z - A.focus) / (max(z, 1e-6) * A.focus);
  return c;
}
// dof::nearShare.
float nearShare(float coc) {
  precise const float s = (-coc - kZoneOfFocusCoc) / kZoneOfFocusCoc;
  return clamp(s, 0.0, 1.0);
}

// LensRays::rasterColour (reuse_raster): the sharp colour where the sharp image shows the hit
// (its depth there within 1 %).
bool rasterColour(RtDofView view, vec3 hit, float zHit, out vec3 rgb) {
  rgb = vec3(0.0);
  if (view.camera.orthographic != 0) return false;
  const float m[16] = view.viewProj;
  precise const float cx = m[0] * hit.x + m[1] * hit.y + m[2] * hit.z + m[3];
  precise const float cy = m[4] * hit.x + m[5] * hit.y + m[6] * hit.z + m[7];
  precise const float cw = m[12] * hit.x + m[13] * hit.y + m[14] * hit.z + m[15];
  if (cw <= 1e-8) return false;
  precise const float iw = 1.0 / cw;
  precise const float px = (cx * iw * 0.5 + 0.5) * float(view.width);
  precise const float py = (0.5 - cy * iw * 0.5) * float(view.height);
  const int ix = int(px), iy = int(py);
  if (px < 0.0 || py < 0.0 || ix >= view.width || iy >= view.height) return false;
  const uint at = uint(iy + view.y) * A.frameWidth + uint(ix + view.x);
  const float d = Out(A.depth).v[at];
  if (d <= 0.0) return false;
  precise const float zRaster = view.camera.nearPlane / d;  // reversed-Z: near / z
  if (abs(zRaster - zHit) > 0.01 * zHit) return false;
  Out sharp = Out(A.sharp);
  rgb = vec3(sharp.v[3u * at], sharp.v[3u * at + 1u], sharp.v[3u * at + 2u]);
  return true;
}

// Whitted::shadePrimary: shadows, reflection and refraction of a primary surface, combined.
vec3 shadeWhitted(Surface s, vec3 d) {
  const float om = s.reflectivity, orr = 1.0 - s.opacity;
  float wm, wr, wc;
  effectWeights(om, orr, wm, wr, wc);
  vec3 color = wc * shadePrimary(s, -d);
  if (orr > 0.0) pushRefraction(s, d, vec3(wr), 1, orr);
  if (om > 0.0) pushReflection(s, d, vec3(wm), 1, om);
  return color + traceStack();
}

void main() {
  A = ArgsRef(args).a;
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= int(A.maskWidth) || y >= int(A.maskHeight)) return;
  useScene(A.scene);
  if (A.shadowMaps != 0ul) useShadowMaps(A.shadowMaps);
  whitted = WhittedConfig(A.maxDepth, A.importanceCutoff, A.shadowCull, A.flags);
  const uint pixel = uint(y) * A.maskWidth + uint(x);
  const int count = int(Out(A.mask).v[pixel]);
  precise vec3 nearRgb = vec3(0.0), farRgb = vec3(0.0), farPos = vec3(0.0);
  precise float nearW = 0.0, farW = 0.0, nearCoc = 0.0, farCoc = 0.0, farPosW = 0.0;
  uint surfaces = 0u, reused = 0u;
  if (count > 0) {
    // The view this mask pixel's frame pixels belong to (viewAt: the first holding it).
    const int fx = min(int((float(x) + 0.5) * A.scale), int(A.frameWidth) - 1);
    const int fy = min(int((float(y) + 0.5) * A.scale), int(A.frameHeight) - 1);
    uint vi = 0u;
    for (uint k = A.viewCount; k-- > 0u;) {
      const RtDofView w = Views(A.views).v[k];
      if (fx >= w.x && fy >= w.y && fx < w.x + w.camera.width && fy < w.y + w.camera.height)
        vi = k;
    }
    const RtDofView view = Views(A.views).v[vi];
    const GpuCamera cam = view.camera;
    const vec3 eye = vec3(cam.eye[0], cam.eye[1], cam.eye[2]);
    const vec3 forward = vec3(cam.forward[0], cam.forward[1], cam.forward[2]);
    const ThinLensRays L = ThinLensRays(A.apertureRadius, A.focus, A.apertureRotation,
                                        A.apertureBlades);
    const uint64_t seed = (uint64_t(A.seedHi) << 32) | uint64_t(A.seedLo);
    for (int i = 0; i < count; ++i) {
      startSampler(seed, uint64_t(pixel), uint(i));
      const vec2 j = uniform2(), l = uniform2();
      vec3 o, d;
      precise const vec2 p = vec2((float(x) + j.x) * A.scale - float(view.x),
                                  (float(y) + j.y) * A.scale - float(view.y));
      thinLensRay(cam, L, p, l, o, d);
      const float tnear = A.nearT / max(dot(d, forward), 1e-6);
      TraceHit h;
      ++rays;
      const bool found = traverse(o, d, tnear, 1e30, TRACE_FILTERED | TRACE_CULL_BACK, h);
      vec3 rgb;
      float z;
      if (!found) {
        z = 1e30;
        rgb = skyRadiance(d);
      } else {
        precise const vec3 hit = o + d * h.t;
        z = dot(hit - eye, forward);
        if (A.sharp != 0ul && rasterColour(view, hit, z, rgb)) {
          ++reused;
        } else {
          const Surface s = resolveSurface(h.object, h.prim, o, d, h.t, h.u, h.v, A.spread);
          rgb = shadeWhitted(s, d);
          ++surfaces;
        }
      }
      const float c = cocOf(z), wn = nearShare(c), wf = 1.0 - wn;
      nearRgb += rgb * wn;
      farRgb += rgb * wf;
      nearW += wn;
      farW += wf;
      nearCoc += wn * abs(c);
      farCoc += wf * min(abs(c), 1e6);
      if (found && wf > 0.0) {
        farPos = farPos + o * wf + d * (h.t * wf);
        farPosW += wf;
      }
    }
  }
  // writePixel: the four outputs.
  precise const float in_ = nearW > 0.0 ? 1.0 / nearW : 0.0;
  precise const float inf_ = farW > 0.0 ? 1.0 / farW : 0.0;
  Out o = Out(A.rtNear);
  o.v[4u * pixel] = nearRgb.x * in_;
  o.v[4u * pixel + 1u] = nearRgb.y * in_;
  o.v[4u * pixel + 2u] = nearRgb.z * in_;
  o.v[4u * pixel + 3u] = nearCoc * in_;
  o = Out(A.rtFar);
  o.v[4u * pixel] = farRgb.x * inf_;
  o.v[4u * pixel + 1u] = farRgb.y * inf_;
  o.v[4u * pixel + 2u] = farRgb.z * inf_;
  o.v[4u * pixel + 3u] = farCoc * inf_;
  o = Out(A.rtHit);
  o.v[2u * pixel] = count > 0 ? nearW / float(count) : 0.0;
  o.v[2u * pixel + 1u] = float(max(count, 0));
  o = Out(A.rtFarPosition);
  precise const float ip = farPosW > 0.0 ? 1.0 / farPosW : 0.0;
  o.v[4u * pixel] = farPos.x * ip;
  o.v[4u * pixel + 1u] = farPos.y * ip;
  o.v[4u * pixel + 2u] = farPos.z * ip;
  o.v[4u * pixel + 3u] = farPosW > 0.0 ? 1.0 : 0.0;
  Counts counts = Counts(A.counters);
  if (rays > 0u) atomicAdd(counts.v[TD_COUNT_RAYS], rays);
  if (surfaces > 0u) {
    atomicAdd(counts.v[TD_COUNT_CULLED], culled);
    atomicAdd(counts.v[TD_COUNT_TRACED], traced);
    if (shadowLit > 0u) atomicAdd(counts.v[TD_COUNT_LIT], shadowLit);
    if (shadowShadowed > 0u) atomicAdd(counts.v[TD_COUNT_SHADOWED], shadowShadowed);
    atomicAdd(counts.v[TD_COUNT_SURFACES], surfaces);
  }
  if (count > 0) atomicAdd(counts.v[TD_COUNT_N + TD_RT_DOF_LENS_RAYS], uint(count));
  if (reused > 0u) atomicAdd(counts.v[TD_COUNT_N + TD_RT_DOF_REUSED], reused);
}
