#version 460
// tandem reference on the GPU, one invocation a pixel and one sample a dispatch, what
// renderReference computes (rt/reference_render.cpp): the same Owen-scrambled Sobol samples
// (rt/sampler.cpp) for the pixel position, the lens point, the shutter time (the camera and the
// moving objects where they are then) and the path, then the
// path tracer (rt/path_tracer.cpp: next-event estimation to punctual lights and emissive
// triangles with MIS, Fresnel glass, mirrors, Lambert + normalised Blinn-Phong, Russian roulette)
// or distributed ray tracing of the hybrids' shading (whitted.glsl), or Peres 2022's diffuse global
// illumination (rt/diffuse_gi.cpp: a light picked by the LightGrid, one cosine bounce).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "light_grid_data.h"
#include "reference_args.h"
#include "scene_data.h"
#include "whitted_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { uint64_t args; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ArgsRef {
  ReferenceArgs a;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Emitters {
  GpuEmitter e[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Ints { int v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Sums { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Counts { uint v[]; };

ReferenceArgs A;

#include "camera.glsl"
#include "scene.glsl"
#include "whitted.glsl"
#include "diffuse_gi.glsl"

#include "sobol.glsl"
#include "thin_lens.glsl"

// ---- The path tracer (rt/path_tracer.cpp).
float fresnelDielectric(float cosi, float eta) {
  const float sin2t = eta * eta * (1.0 - cosi * cosi);
  if (sin2t >= 1.0) return 1.0;
  const float cost = sqrt(1.0 - sin2t);
  const float rs = (eta * cosi - cost) / (eta * cosi + cost);
  const float rp = (cosi - eta * cost) / (cosi + eta * cost);
  return 0.5 * (rs * rs + rp * rp);
}
vec3 sampleBlinnHalf(vec3 n, float e, float u1, float u2) {
  const float cosT = pow(u1, 1.0 / (e + 1.0));
  const float sinT = sqrt(max(0.0, 1.0 - cosT * cosT)), phi = 2.0 * kPi * u2;
  return toWorld(vec3(sinT * cos(phi), sinT * sin(phi), cosT), n);
}
float average(vec3 v) { return (v.x + v.y + v.z) * (1.0 / 3.0); }
float powerHeuristic(float p, float q) { return p * p / (p * p + q * q); }

// brdfAndPdf: the BRDF and the mixture density (cosine with probability pd, else Blinn-Phong).
vec3 brdfAndPdf(vec3 n, vec3 wo, vec3 wi, vec3 kd, vec3 ks, float pd, float e, out float pdf) {
  const float cosI = dot(n, wi);
  const bool glossy = maxComponent(ks) > 0.0, lobe = cosI > 0.0 && pd < 1.0;
  vec3 h = vec3(0.0);
  float cosPow = 0.0;
  if (glossy || lobe) {
    h = normalize(wo + wi);
    cosPow = pow(max(dot(n, h), 0.0), e);
  }
  const vec3 f = glossy ? kd * (1.0 / kPi) + ks * ((e + 8.0) / (8.0 * kPi) * cosPow) : kd * (1.0 / kPi);
  if (cosI <= 0.0)
    pdf = 0.0;
  else if (pd >= 1.0)
    pdf = cosI / kPi;
  else
    pdf = pd * cosI / kPi +
          (1.0 - pd) * ((e + 1.0) / (2.0 * kPi) * cosPow) / max(4.0 * dot(wo, h), 1e-6);
  return f;
}

float emitterPdf(int object, int prim) {
  if (A.emitterCount == 0u || object < 0) return 0.0;
  const int first = Ints(A.objectFirst).v[object];
  return first < 0 ? 0.0 : Emitters(A.emitters).e[first + prim].pdfArea;
}

bool closestHit(vec3 o, vec3 d, float tnear, float tfar, bool cullBack, out TraceHit h) {
  ++rays;
  return traverse(o, d, tnear, tfar, TRACE_FILTERED | (cullBack ? TRACE_CULL_BACK : 0u), h);
}

vec3 areaLight(Surface s, vec3 wo, vec3 kd, vec3 ks, float pd) {
  const float u = uniform1();
  const vec2 uv = uniform2();
  // EmitterTable::sample: the first triangle whose cumulative weight reaches u.
  Emitters em = Emitters(A.emitters);
  int lo = 0, hi = int(A.emitterCount) - 1;
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (em.e[mid].cdf < u)
      lo = mid + 1;
    else
      hi = mid;
  }
  const GpuEmitter t = em.e[lo];
  if (!(t.pdfArea > 0.0)) return vec3(0.0);
  const GpuObject ob = Objects(S.objects).o[t.object];
  const uvec3 k = triangleVertices(ob, t.prim);
  const float su = sqrt(uv.x);
  const vec3 x = vertexPositionAt(ob, k.x) * (1.0 - su) +
                 vertexPositionAt(ob, k.y) * (su * (1.0 - uv.y)) + vertexPositionAt(ob, k.z) * (su * uv.y);
  const vec3 toL = x - s.position;
  const float dist = length(toL);
  if (!(dist > 0.0)) return vec3(0.0);
  const vec3 wi = toL / dist;
  const float cosI = dot(s.normal, wi);
  if (cosI <= 0.0) return vec3(0.0);
  TraceHit h;
  const vec3 o = offsetRayOrigin(s, wi);
  if (!closestHit(o, wi, 0.0, dist * 1.001 + 1e-4, false, h) || h.object != t.object ||
      h.prim != t.prim)
    return vec3(0.0);
  const Surface e = resolveSurface(h.object, h.prim, o, wi, h.t, h.u, h.v, 0.0);
  const float cosL = -dot(e.geoNormal, wi);
  if (!(cosL > 1e-6)) return vec3(0.0);
  const float pdfLight = t.pdfArea * h.t * h.t / cosL;
  float pdf;
  const vec3 f = brdfAndPdf(s.normal, wo, wi, kd, ks, pd, s.specularExponent, pdf);
  return f * e.emission * (cosI * powerHeuristic(pdfLight, pdf) / pdfLight);
}

vec3 directLight(Surface s, vec3 wo, vec3 kd, vec3 ks) {
  vec3 sum = vec3(0.0);
  Lights lights = Lights(S.lights);
  for (uint i = 0u; i < S.lightCount; ++i) {
    if (Uints(A.lightSkip).v[i] != 0u) continue;
    const GpuLight l = lights.l[i];
    vec3 wi, radiance;
    float dist;
    sampleLight(l, s.position, wi, dist, radiance);
    const float cosI = dot(s.normal, wi);
    if (cosI <= 0.0 || maxComponent(radiance) <= 0.0) continue;
    if (l.castsShadows != 0u) {
      ++rays;
      TraceHit h;
      const float tfar = isinf(dist) ? kInf : dist * (1.0 - 1e-4);
      if (traverse(offsetRayOrigin(s, wi), wi, 0.0, tfar, TRACE_ANY | TRACE_FILTERED, h)) continue;
    }
    float pdf;
    sum += brdfAndPdf(s.normal, wo, wi, kd, ks, 1.0, s.specularExponent, pdf) * radiance * cosI;
  }
  return sum;
}

// PathTracer::radiance: the camera ray from its origin (no near plane), culling back faces.
vec3 pathRadiance(vec3 o, vec3 d) {
  vec3 L = vec3(0.0), beta = vec3(1.0);
  float lastPdf = 0.0;
  for (int depth = 0; depth < A.maxDepth; ++depth) {
    TraceHit hit;
    if (!closestHit(o, d, 0.0, 1e30, depth == 0, hit)) {
      L += beta * skyRadiance(d);
      break;
    }
    Surface s = resolveSurface(hit.object, hit.prim, o, d, hit.t, hit.u, hit.v, 0.0);
    if (maxComponent(s.emission) > 0.0 && dot(s.geoNormal, d) < 0.0) {
      float w = 1.0;
      if (lastPdf > 0.0) {
        const float cosL = -dot(s.geoNormal, d);
        const float pdfLight =
            cosL > 1e-6 ? emitterPdf(hit.object, hit.prim) * hit.t * hit.t / cosL : 0.0;
        w = powerHeuristic(lastPdf, pdfLight);
      }
      L += beta * s.emission * w;
    }
    lastPdf = 0.0;
    const float t = 1.0 - s.opacity, m = (1.0 - t) * s.reflectivity;
    const float lobe = uniform1();
    const vec3 facing = dot(s.normal, d) > 0.0 ? -s.normal : s.normal;
    if (lobe < t) {
      const bool entering = dot(s.geoNormal, d) < 0.0;
      const float eta = entering ? S.environmentIor / s.ior : s.ior / S.environmentIor;
      const float cosi = -dot(d, facing);
      const float k = 1.0 - eta * eta * (1.0 - cosi * cosi);
      if (uniform1() < fresnelDielectric(cosi, eta) || k < 0.0) {
        d = reflectDir(d, facing);
      } else {
        d = d * eta + facing * (eta * cosi - sqrt(k));
        beta *= v3(Materials(S.materials).m[s.material].transmissionFilter);
      }
      d = normalize(d);
    } else if (lobe < t + m) {
      d = normalize(reflectDir(d, facing));
    } else {
      vec3 kd = max(s.diffuse, vec3(0.0)), ks = max(s.specular, vec3(0.0));
      const float total = maxComponent(kd + ks);
      if (total > 1.0) kd /= total, ks /= total;
      s.normal = facing;
      const vec3 wo = -d;
      L += beta * directLight(s, wo, kd, ks);
      const float wd = average(kd), wsp = average(ks);
      if (wd + wsp <= 0.0) break;
      const float pd = wd / (wd + wsp), e = s.specularExponent;
      if (A.emitterCount > 0u) L += beta * areaLight(s, wo, kd, ks, pd);
      const float which = uniform1();
      const vec2 u = uniform2();
      const vec3 wi = which < pd ? sampleCosine(facing, u.x, u.y)
                                 : reflectDir(d, sampleBlinnHalf(facing, e, u.x, u.y));
      const float cosI = dot(facing, wi);
      if (cosI <= 0.0) break;
      float pdf;
      const vec3 f = brdfAndPdf(facing, wo, wi, kd, ks, pd, e, pdf);
      if (!(pdf > 0.0)) break;
      beta *= f * (cosI / pdf);
      d = normalize(wi);
      lastPdf = pdf;
    }
    o = offsetRayOrigin(s, d);
    if (depth + 1 >= A.rouletteDepth) {
      const float q = min(maxComponent(beta), 0.95);
      if (!(q > 0.0) || uniform1() >= q) break;
      beta /= q;
    }
  }
  return L;
}

// Distributed ray tracing of the hybrids' shading (whittedRadiance): the camera ray from the
// near plane culling back faces, then Whitted::shadePrimary.
vec3 whittedRadiance(GpuCamera c, vec3 o, vec3 d) {
  const vec3 forward = vec3(c.forward[0], c.forward[1], c.forward[2]);
  TraceHit h;
  if (!closestHit(o, d, c.nearPlane / max(dot(d, forward), 1e-6), 1e30, true, h))
    return skyRadiance(d);
  const Surface s = resolveSurface(h.object, h.prim, o, d, h.t, h.u, h.v, 0.0);
  const float om = s.reflectivity, orr = 1.0 - s.opacity;
  float wm, wr, wc;
  effectWeights(om, orr, wm, wr, wc);
  vec3 color = wc * shadePrimary(s, -d);
  if (orr > 0.0) pushRefraction(s, d, vec3(wr), 1, orr);
  if (om > 0.0) pushReflection(s, d, vec3(wm), 1, om);
  return color + traceStack();
}

// DiffuseGI::radiance of the surface a pinhole ray through the pixel centre meets (the foveated
// path tracer's G-buffer surface), seen along wo.
vec3 diffuseGIRadiance(GpuCamera c, int x, int y) {
  vec3 o, d;
  float tnear;
  cameraRay(c, x, y, o, d, tnear);
  TraceHit h;
  if (!closestHit(o, d, tnear, 1e30, true, h)) return skyRadiance(d);
  const Surface s = resolveSurface(h.object, h.prim, o, d, h.t, h.u, h.v, A.pixelSpread);
  const vec2 u0 = uniform2(), u1 = uniform2(), u2 = uniform2();
  return giRadiance(s, -d, u0, u1, u2);
}

// cameraAtShutter (rt/reference_render.cpp): the camera moved to its position and lookAt at
// shutter fraction tau, its axes as Camera::make draws them (Mat4::lookAt).
GpuCamera cameraAtShutter(GpuCamera c, float tau) {
  const vec3 eye = lerp3(v3(c.position), v3(A.closePosition), tau);
  const vec3 target = lerp3(v3(A.openLookAt), v3(A.closeLookAt), tau);
  const vec3 f = safeNormalize(target - eye);
  vec3 s = safeNormalize(cross(f, v3(A.cameraUp)));
  if (length(s) == 0.0) s = safeNormalize(cross(f, abs(f.y) < 0.9 ? vec3(0, 1, 0) : vec3(1, 0, 0)));
  const vec3 u = cross(s, f);
  for (int i = 0; i < 3; ++i) {
    c.position[i] = eye[i];
    c.eye[i] = eye[i];
    c.forward[i] = f[i];
    c.right[i] = s[i];
    c.up[i] = u[i];
  }
  return c;
}

void main() {
  A = ArgsRef(args).a;
  const GpuCamera cam = CameraRef(A.camera).c;
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= cam.width || y >= cam.height) return;
  if ((uint(y) / A.stripeRows) % A.ranks != A.rank) return;  // another process's row: left at 0
  useScene(A.scene);
  giGrid = A.grid;
  whitted = WhittedConfig(A.whittedDepth, A.importanceCutoff, A.shadowCull, A.whittedFlags);
  const uint64_t seed = (uint64_t(A.seedHi) << 32) | uint64_t(A.seedLo);
  const uint64_t pixel = uint64_t(y) * uint64_t(cam.width) + uint64_t(x);
  // One sample a dispatch, added to the pixel's sums (no other invocation writes them).
  startSampler(seed, pixel, A.first);
  const vec2 jitter = uniform2(), lens = uniform2();
  const float tau = uniform1();  // the shutter time
  vec3 L;
  if (A.integrator == TD_REFERENCE_DIFFUSE_GI) {
    L = diffuseGIRadiance(cam, x, y);  // the G-buffer's surface: shutter open, as on the CPU
  } else {
    traceTau = tau;
    const GpuCamera c = A.cameraMoves != 0u ? cameraAtShutter(cam, tau) : cam;
    vec3 o, d;
    const ThinLensRays thin =
        ThinLensRays(A.apertureRadius, A.focusDistance, A.apertureRotation, A.apertureBlades);
    thinLensRay(c, thin, vec2(float(x), float(y)) + jitter, lens, o, d);
    L = A.integrator == TD_REFERENCE_WHITTED ? whittedRadiance(c, o, d) : pathRadiance(o, d);
  }
  if (any(isnan(L)) || any(isinf(L))) L = vec3(0.0);  // a degenerate pdf spoils no pixel
  const float lum = luminance(L);
  Sums sums = Sums(A.sums);
  const uint at = 4u * (uint(y) * uint(cam.width) + uint(x));
  sums.v[at] += L.x;
  sums.v[at + 1u] += L.y;
  sums.v[at + 2u] += L.z;
  sums.v[at + 3u] += lum * lum;
  atomicAdd(Counts(A.counters).v[0], rays);
}
