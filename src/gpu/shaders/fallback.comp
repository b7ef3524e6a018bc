#version 460
// ss_fallback on the GPU, one invocation a pixel, what ScreenSpaceFallbackPass::execute computes
// for the effects the heuristic left untraced: a mirror's or glass's stand-in (the sky, a
// screen-space march through the frame, or the object's reflection probe, parallax-corrected and
// refracted out through its bounding sphere) and the shadow term S from the frame's shadow maps
// (shadow_term.glsl with the maps deciding every pair). Phase TD_FALLBACK_COUNT counts, per
// object, the pixels showing an untraced effect: the host picks which objects get probes.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "fallback_args.h"
#include "gbuffer_args.h"
#include "scene_data.h"
#include "shadow_maps_data.h"
#include "whitted_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { FallbackArgs a; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Counts { uint v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer MarchRef {
  FallbackView m;
};
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ProbesRef {
  GpuProbe p[];
};

#include "camera.glsl"
#include "scene.glsl"
#include "gbuffer.glsl"
#include "shadow_maps.glsl"
#include "whitted.glsl"
#include "shadow_term.glsl"

const int kReflection = 0, kRefraction = 3, kShadow = 6, kCoversEffect = 9, kCoversShadow = 10;
const int kChannels = 11;

// refractDir (rt/whitted.cpp): false on total internal reflection.
bool refractInto(vec3 d, vec3 n, float eta, out vec3 t) {
  const float cosi = -dot(d, n);
  const float k = 1.0 - eta * eta * (1.0 - cosi * cosi);
  if (k < 0.0) return false;
  t = safeNormalize(d * eta + n * (eta * cosi - sqrt(k)));
  return true;
}

float rowDot(float m[16], int r, vec4 q) {
  return m[4 * r] * q.x + m[4 * r + 1] * q.y + m[4 * r + 2] * q.z + m[4 * r + 3] * q.w;
}

// marchScreen: the first frame pixel whose surface the march from p along r passes just behind
// (skipping `self` for refraction, which takes the first surface it passes behind however far),
// else the sky; a mirror or glass pixel stands in by the sky too.
vec3 marchScreen(GpuView view, FallbackView fv, GBufferTargets g, vec3 p, vec3 r, int self) {
  const GpuCamera cam = view.camera;
  const vec4 c0 = vec4(rowDot(fv.viewProj, 0, vec4(p, 1.0)), rowDot(fv.viewProj, 1, vec4(p, 1.0)),
                       rowDot(fv.viewProj, 2, vec4(p, 1.0)), rowDot(fv.viewProj, 3, vec4(p, 1.0)));
  const vec4 cr = vec4(rowDot(fv.viewProj, 0, vec4(r, 0.0)), rowDot(fv.viewProj, 1, vec4(r, 0.0)),
                       rowDot(fv.viewProj, 2, vec4(r, 0.0)), rowDot(fv.viewProj, 3, vec4(r, 0.0)));
  const vec3 eye = v3(cam.eye), forward = v3(cam.forward);
  const float z0 = dot(p - eye, forward), zr = dot(r, forward);
  float t = 0.01;
  for (int i = 0; i < a.steps; ++i, t *= fv.growth) {
    const vec4 c = c0 + cr * t;
    if (c.w <= 1e-6) break;  // behind the eye
    const float iw = 1.0 / c.w;
    const float sx = (c.x * iw * 0.5 + 0.5) * float(cam.width);
    const float sy = (0.5 - c.y * iw * 0.5) * float(cam.height);
    if (!(sx >= 0.0 && sy >= 0.0 && sx < float(cam.width) && sy < float(cam.height))) break;
    const uint q = uint(int(sy) + a.viewY) * uint(a.frameWidth) + uint(int(sx) + a.viewX);
    const int id = int(Target(g.objectId).v[q]);
    if (id < 0 || id == self) continue;
    const float surface = dot(get3(g.position, q) - eye, forward);
    const float behind = z0 + zr * t - surface;
    if (behind > 0.0 && (self >= 0 || behind < a.thickness * t + 0.02)) {
      const vec3 op = get3(g.optical, q);
      if (op.x > 0.0 || op.z < 1.0) break;
      return get3(a.hdr, q);
    }
  }
  return skyRadiance(r);
}

// ReflectionProbes::lookup: the radiance at the probe's centre from direction d (bilinear
// within a face), the sky where the object has no probe.
vec3 probeLookup(GpuProbe pr, vec3 d) {
  if (pr.size == 0) return skyRadiance(d);
  const int f = cubeFaceOf(d);
  const vec4 q = vec4(v3(pr.centre) + d, 1.0);
  float m[16];
  for (int k = 0; k < 16; ++k) m[k] = pr.viewProj[f][k];
  const float w = rowDot(m, 3, q);
  if (w <= 1e-8) return skyRadiance(d);
  const float iw = 1.0 / w;
  const int n = pr.size;
  const float px = (rowDot(m, 0, q) * iw * 0.5 + 0.5) * float(n);
  const float py = (0.5 - rowDot(m, 1, q) * iw * 0.5) * float(n);
  const float fx = clamp(px - 0.5, 0.0, float(n - 1)), fy = clamp(py - 0.5, 0.0, float(n - 1));
  const int x0 = int(fx), y0 = int(fy), x1 = min(x0 + 1, n - 1), y1 = min(y0 + 1, n - 1);
  const float tx = fx - float(x0), ty = fy - float(y0);
  const uint base = uint(f) * uint(n) * uint(n);
  const vec3 c00 = get3(pr.faces, base + uint(y0 * n + x0)),
             c10 = get3(pr.faces, base + uint(y0 * n + x1)),
             c01 = get3(pr.faces, base + uint(y1 * n + x0)),
             c11 = get3(pr.faces, base + uint(y1 * n + x1));
  return (c00 * (1.0 - tx) + c10 * tx) * (1.0 - ty) + (c01 * (1.0 - tx) + c11 * tx) * ty;
}

// ReflectionProbes::lookupFrom: parallax-corrected against the scene's box.
vec3 probeLookupFrom(GpuProbe pr, FallbackView fv, vec3 p, vec3 d) {
  if (pr.size == 0) return skyRadiance(d);
  float far = kInf;
  for (int k = 0; k < 3; ++k) {
    if (p[k] < fv.boundsLo[k] || p[k] > fv.boundsHi[k]) return probeLookup(pr, d);
    if (d[k] > 0.0) far = min(far, (fv.boundsHi[k] - p[k]) / d[k]);
    if (d[k] < 0.0) far = min(far, (fv.boundsLo[k] - p[k]) / d[k]);
  }
  if (isinf(far)) return probeLookup(pr, d);
  const vec3 towards = p + d * far - v3(pr.centre);
  const float len = length(towards);
  return probeLookup(pr, len > 0.0 ? towards / len : d);
}

// ReflectionProbes::exitDirection: out through the object's bounding sphere, refracted
// (eta = ior inside / outside) or reflected back in on total internal reflection.
vec3 probeExit(GpuProbe pr, vec3 p, vec3 t, float eta, out vec3 exitPoint) {
  exitPoint = p;
  if (pr.size == 0) return t;
  const vec3 oc = p - v3(pr.centre);
  const float bq = dot(oc, t), c = dot(oc, oc) - pr.radius * pr.radius;
  const float disc = bq * bq - c;
  if (disc < 0.0) return t;
  const float s = -bq + sqrt(disc);
  if (!(s > 0.0)) return t;
  exitPoint = p + t * s;
  const vec3 n = safeNormalize(exitPoint - v3(pr.centre));
  vec3 o;
  if (!refractInto(t, -n, eta, o)) o = safeNormalize(t - (-n) * (2.0 * dot(t, -n)));
  return o;
}

vec3 look(GpuView view, FallbackView fv, GBufferTargets g, Surface s, vec3 r, int self) {
  if (a.mode == TD_FALLBACK_PROBE) {
    const GpuProbe pr = ProbesRef(a.probes).p[s.object];
    vec3 from = s.position;
    const vec3 dir = self < 0 ? r : probeExit(pr, s.position, r, s.ior, from);
    return probeLookupFrom(pr, fv, from, dir);
  }
  return a.mode == TD_FALLBACK_ENVIRONMENT ? skyRadiance(r)
                                           : marchScreen(view, fv, g, s.position, r, self);
}

void main() {
  const GpuView view = ViewRef(a.view).v;
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= view.camera.width || y >= view.camera.height) return;
  useScene(a.scene);
  const uint pixel = uint(y + a.viewY) * uint(a.frameWidth) + uint(x + a.viewX);
  const GBufferTargets g = TargetsRef(a.sources).g;
  const vec3 m = get3(a.mask, pixel);
  if (a.phase == TD_FALLBACK_COUNT) {
    const int id = int(Target(g.objectId).v[pixel]);
    if (id < 0) return;
    const vec3 op = get3(g.optical, pixel);
    if ((op.x > 0.0 && m.y < 0.5) || (op.z < 1.0 && m.z < 0.5))
      atomicAdd(Counts(a.areas).v[id], 1u);
    if (op.x > 0.0 || op.z < 1.0) atomicAdd(Counts(a.areas).v[a.objectCount + uint(id)], 1u);
    return;
  }
  float out_[kChannels];
  for (int k = 0; k < kChannels; ++k) out_[k] = 0.0;
  Surface s;
  if (readSurface(g, pixel, s)) {
    const bool reflect = a.mode != TD_FALLBACK_OFF && s.reflectivity > 0.0 && m.y < 0.5;
    const bool refract = a.mode != TD_FALLBACK_OFF && s.opacity < 1.0 && m.z < 0.5;
    if (reflect || refract) {
      const FallbackView fv = MarchRef(a.march).m;
      vec3 o, d;
      float tnear;
      cameraRay(view.camera, x, y, o, d, tnear);
      vec3 n = s.normal;
      if (dot(n, d) > 0.0) n = -n;
      if (reflect) {
        const vec3 c = look(view, fv, g, s, safeNormalize(reflectDir(d, n)), -1);
        out_[kReflection] = c.x, out_[kReflection + 1] = c.y, out_[kReflection + 2] = c.z;
      }
      if (refract) {
        vec3 t;
        if (!refractInto(d, n, 1.0 / max(s.ior, 1e-3), t)) t = reflectDir(d, n);
        const vec3 c = look(view, fv, g, s, t, s.object);
        out_[kRefraction] = c.x, out_[kRefraction + 1] = c.y, out_[kRefraction + 2] = c.z;
      }
      out_[kCoversEffect] = 1.0;
    }
    if (a.shadowMaps != 0ul && !(m.x > 0.5)) {
      useShadowMaps(a.shadowMaps);
      whitted = WhittedConfig(0, 0.0, a.shadowCull, TD_WHITTED_MAPS);
      // The eye direction as deferred shading takes it.
      const vec3 wo = view.perspective != 0 ? safeNormalize(v3(view.camera.eye) - s.position)
                                            : -v3(view.camera.forward);
      vec3 shares;
      const vec3 sh = shadowTerm(s, wo, -1, shares);
      out_[kShadow] = sh.x, out_[kShadow + 1] = sh.y, out_[kShadow + 2] = sh.z;
      out_[kCoversShadow] = 1.0;
    }
  }
  Target t = Target(a.result);
  for (int k = 0; k < kChannels; ++k) t.v[uint(kChannels) * pixel + uint(k)] = out_[k];
}
