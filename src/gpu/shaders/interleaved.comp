#version 460
// interleaved_rt on the GPU (Foster 2015; Fatahalian et al. 2009), one stage a dispatch over one
// view, what InterleavedPass::renderView computes: a pair's samples (the CPU's layout: position
// and pair) each traced from its pair's camera, back faces culled, and shaded at the pair's time
// (moving objects met where they are then: traceTau) as the CPU shades them, Whitted's
// shadows, mirrors and glass or local Blinn-Phong; the samples resolved to pixels by the box or
// Blackman-Harris filter (the CPU's table); each pixel's first sample's velocity over the shutter,
// view depth and motion since the previous frame. With a sample mask only the samples within the
// filter's reach of it are traced, and pixels outside it are 0. With `shading_rate = pixel` the
// samples' visibility comes first (the raster's, or each pair's samples traced into the same
// keys), then each pixel's representatives, then the shading of those alone.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "bvh.h"
#include "interleaved_args.h"
#include "scene_data.h"
#include "shadow_maps_data.h"
#include "whitted_args.h"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { InterleavedPush p; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ArgsRef {
  InterleavedArgs a;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Pairs { IlPair v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Carries {
  IlCarry v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Out { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Words { uint v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Keys { uint64_t v[]; };

InterleavedArgs A;

#include "camera.glsl"
#include "scene.glsl"
#include "shadow_maps.glsl"
#include "whitted.glsl"

const uint kRowEntries = 64u * 64u;  // entries per row of groups (the host's dispatch)

vec2 samplePos(uint id) {
  Out l = Out(A.samplePos);
  return vec2(l.v[2u * id], l.v[2u * id + 1u]);
}
uint samplePair(uint id) { return Words(A.samplePair).v[id]; }

// Step 0 (markActive): a sample is needed when a mask pixel lies within the filter's reach of
// its pixel.
bool activeSample(uint id) {
  if (A.mask == 0ul) return true;
  const int sw = A.width * A.sx;
  const int qx = int(id % uint(sw)) / A.sx, qy = int(id / uint(sw)) / A.sy;
  Out mask = Out(A.mask);
  for (int y = max(0, qy - A.reach); y <= min(A.height - 1, qy + A.reach); ++y)
    for (int x = max(0, qx - A.reach); x <= min(A.width - 1, qx + A.reach); ++x)
      if (mask.v[uint(y + A.viewY) * A.frameWidth + uint(x + A.viewX)] > 0.0) return true;
  return false;
}

// TD_IL_TRACE: a pair's samples traced (InterleavedRTPass::visibility), each hit kept as the
// rasterizer keeps it (its triangle's index over all objects, inverted, in the low word; 0 for
// the sky), so that representatives are found and shaded as the raster's are.
void traceSample(uint k) {
  if (k >= p.count) return;
  const uint id = Words(A.ids).v[p.begin + k];
  if (!activeSample(id)) return;
  vec3 o, d;
  float tnear;
  const IlPair pair = Pairs(A.pairs).v[p.pair];
  traceTau = pair.tau;
  cameraRayAt(pair.camera, samplePos(id), o, d, tnear);
  TraceHit h;
  const bool found = traverse(o, d, 0.0, 1e30, TRACE_FILTERED | TRACE_CULL_BACK, h);
  uint64_t key = 0ul;
  if (found) {
    const uint triangle = Objects(S.objects).o[h.object].firstIndex / 3u + uint(h.prim);
    key = (uint64_t(1u) << 32) | uint64_t(~triangle);
  }
  Keys(A.visibility).v[id] = key;
  atomicAdd(Words(A.counters).v[TD_COUNT_RAYS], 1u);
}

void shade(uint k) {
  if (k >= p.count) return;
  const uint id = Words(A.ids).v[p.begin + k];
  if (!activeSample(id)) return;
  if ((A.flags & TD_IL_PER_PIXEL) != 0u && Words(A.rep).v[id] != id) return;
  const IlPair pair = Pairs(A.pairs).v[p.pair];
  traceTau = pair.tau;  // moving objects where they are at the pair's time
  vec3 o, d;
  float tnear;
  cameraRayAt(pair.camera, samplePos(id), o, d, tnear);
  TraceHit h;
  bool found;
  if ((A.flags & (TD_IL_RASTER | TD_IL_PER_PIXEL)) != 0u) {
    // The triangle the visibility keys hold, intersected by the sample's camera ray (as the CPU
    // resolves it).
    const uint64_t key = Keys(A.visibility).v[id];
    found = key != 0ul;
    if (found) {
      const uint triangle = ~uint(key & 0xfffffffful);
      h.object = objectOfTriangle(triangle, uint(A.objectCount));
      const GpuObject ob = Objects(S.objects).o[h.object];
      h.prim = int(triangle - ob.firstIndex / 3u);
      const uvec3 k = triangleVertices(ob, h.prim);
      intersectTriangle(o, d, vertexPositionAt(ob, k.x), vertexPositionAt(ob, k.y),
                        vertexPositionAt(ob, k.z), h.t,
                        h.u, h.v);
    }
  } else {
    ++rays;
    found = traverse(o, d, 0.0, 1e30, TRACE_FILTERED | TRACE_CULL_BACK, h);
  }
  vec3 c;
  Out position = Out(A.position);
  if (!found) {
    c = skyRadiance(d);
  } else {
    const Surface s = resolveSurface(h.object, h.prim, o, d, h.t, h.u, h.v, A.spread);
    if ((A.flags & TD_IL_WHITTED) != 0u) {
      const float om = s.reflectivity, orr = 1.0 - s.opacity;
      float wm, wr, wc;
      effectWeights(om, orr, wm, wr, wc);
      c = wc * shadePrimary(s, -d);
      if (orr > 0.0) pushRefraction(s, d, vec3(wr), 1, orr);
      if (om > 0.0) pushReflection(s, d, vec3(wm), 1, om);
      c += traceStack();
    } else {
      c = shadeUnshadowed(s, -d);
    }
    position.v[3u * id] = s.position.x;
    position.v[3u * id + 1u] = s.position.y;
    position.v[3u * id + 2u] = s.position.z;
  }
  Out colour = Out(A.colour);
  colour.v[3u * id] = c.x, colour.v[3u * id + 1u] = c.y, colour.v[3u * id + 2u] = c.z;
  Words(A.object).v[id] = found ? uint(h.object) : 0xffffffffu;
  Words counts = Words(A.counters);
  atomicAdd(counts.v[TD_COUNT_RAYS], rays);
  if (found && (A.flags & TD_IL_WHITTED) != 0u) {
    atomicAdd(counts.v[TD_COUNT_CULLED], culled);
    atomicAdd(counts.v[TD_COUNT_TRACED], traced);
    if (shadowLit > 0u) atomicAdd(counts.v[TD_COUNT_LIT], shadowLit);
    if (shadowShadowed > 0u) atomicAdd(counts.v[TD_COUNT_SHADOWED], shadowShadowed);
    atomicAdd(counts.v[TD_COUNT_SURFACES], 1u);
  }
}

float filterWeight(float d) {
  const float x = abs(d);
  return x > A.radius ? 0.0 : Out(A.weights).v[int(x * A.toTable + 0.5)];
}

void resolvePixel(int px, int py) {
  const uint at = uint(py + A.viewY) * A.frameWidth + uint(px + A.viewX);
  Out hdr = Out(A.hdr);
  if (A.mask != 0ul && !(Out(A.mask).v[at] > 0.0)) {
    hdr.v[3u * at] = 0.0, hdr.v[3u * at + 1u] = 0.0, hdr.v[3u * at + 2u] = 0.0;
    return;
  }
  const float cx = float(px) + 0.5, cy = float(py) + 0.5;
  const int sw = A.width * A.sx;
  Out colour = Out(A.colour);
  vec3 sum = vec3(0.0);
  float wsum = 0.0;
  for (int qy = max(0, py - A.reach); qy <= min(A.height - 1, py + A.reach); ++qy)
    for (int qx = max(0, px - A.reach); qx <= min(A.width - 1, px + A.reach); ++qx)
      for (int sy = 0; sy < A.sy; ++sy)
        for (int sx = 0; sx < A.sx; ++sx) {
          const uint id = uint(qy * A.sy + sy) * uint(sw) + uint(qx * A.sx + sx);
          const vec2 pos = samplePos(id);
          const float w = filterWeight(pos.x - cx) * filterWeight(pos.y - cy);
          if (w <= 0.0) continue;
          sum = sum + vec3(colour.v[3u * id], colour.v[3u * id + 1u], colour.v[3u * id + 2u]) * w;
          wsum += w;
        }
  if (wsum > 1e-12) sum = sum * (1.0 / wsum);
  hdr.v[3u * at] = sum.x, hdr.v[3u * at + 1u] = sum.y, hdr.v[3u * at + 2u] = sum.z;
}

vec4 times(float m[16], vec4 q) {
  return vec4(m[0] * q.x + m[1] * q.y + m[2] * q.z + m[3] * q.w,
              m[4] * q.x + m[5] * q.y + m[6] * q.z + m[7] * q.w,
              m[8] * q.x + m[9] * q.y + m[10] * q.z + m[11] * q.w,
              m[12] * q.x + m[13] * q.y + m[14] * q.z + m[15] * q.w);
}
bool toPixel(float m[16], vec3 q, float w, out vec2 o) {
  const vec4 h = times(m, vec4(q, w));
  o = vec2(0.0);
  if (h.w <= 1e-8) return false;
  o = vec2((h.x / h.w * 0.5 + 0.5) * float(A.width), (0.5 - h.y / h.w * 0.5) * float(A.height));
  return true;
}

// writeMotion: the pixel's first sample carried rigidly with its object to shutter open and
// close (velocity), and to last frame (motion).
void motionPixel(int px, int py) {
  const uint at = uint(py + A.viewY) * A.frameWidth + uint(px + A.viewX);
  Out vel = Out(A.velocity), dep = Out(A.depth), mot = Out(A.motion);
  vel.v[2u * at] = 0.0, vel.v[2u * at + 1u] = 0.0;
  dep.v[at] = 1e30;
  if (A.motion != 0ul) mot.v[2u * at] = 0.0, mot.v[2u * at + 1u] = 0.0;
  const uint id = uint(py * A.sy) * uint(A.width * A.sx) + uint(px * A.sx);
  if (!activeSample(id)) return;
  const uint j = samplePair(id);
  const IlPair pair = Pairs(A.pairs).v[j];
  vec3 pOpen, pClose, pNow, pPrev;
  float wPoint = 1.0;
  const uint object = Words(A.object).v[id];
  if (object == 0xffffffffu) {
    vec3 o;
    float tnear;
    cameraRayAt(pair.camera, samplePos(id), o, pOpen, tnear);
    pClose = pNow = pPrev = pOpen;  // a direction: only the camera's rotation moves it
    wPoint = 0.0;
  } else {
    Out position = Out(A.position);
    const vec3 q = vec3(position.v[3u * id], position.v[3u * id + 1u], position.v[3u * id + 2u]);
    pNow = q;
    pOpen = pClose = pPrev = q;
    if ((A.flags & TD_IL_TIME) != 0u && Words(A.animated).v[object] != 0u) {
      const IlCarry c = Carries(A.carry).v[j * uint(A.objectCount) + object];
      pOpen = times(c.open, vec4(q, 1.0)).xyz;
      pClose = times(c.close, vec4(q, 1.0)).xyz;
      pPrev = times(c.prev, vec4(q, 1.0)).xyz;
    }
    const vec3 eye = vec3(pair.camera.eye[0], pair.camera.eye[1], pair.camera.eye[2]);
    dep.v[at] = dot(q - eye, vec3(pair.camera.forward[0], pair.camera.forward[1],
                                  pair.camera.forward[2]));
  }
  vec2 a, b;
  if (toPixel(A.openViewProj, pOpen, wPoint, a) && toPixel(A.closeViewProj, pClose, wPoint, b)) {
    vel.v[2u * at] = b.x - a.x;
    vel.v[2u * at + 1u] = b.y - a.y;
  }
  if (A.motion != 0ul && toPixel(pair.nowViewProj, pNow, wPoint, a) &&
      toPixel(pair.prevViewProj, pPrev, wPoint, b)) {
    mot.v[2u * at] = a.x - b.x;
    mot.v[2u * at + 1u] = a.y - b.y;
  }
}

// findRepresentatives: the first of the pixel's samples (in order) that sees the same triangle
// (or the sky) at the same pair, or at the same time when the lens does not vary.
void represent(uint id) {
  const int sw = A.width * A.sx;
  const int px = int(id % uint(sw)) / A.sx, py = int(id / uint(sw)) / A.sy;
  Keys keys = Keys(A.visibility);
  Pairs pairs = Pairs(A.pairs);
  const uint triangle = uint(keys.v[id] & 0xfffffffful), j = samplePair(id);
  const bool lens = (A.flags & TD_IL_LENS) != 0u;
  uint rep = id;
  bool done = false;  // reached id, or found its representative
  for (int sy = 0; sy < A.sy && !done; ++sy)
    for (int sx = 0; sx < A.sx && !done; ++sx) {
      const uint q = uint(py * A.sy + sy) * uint(sw) + uint(px * A.sx + sx);
      done = q == id;
      if (done) break;
      const uint jq = samplePair(q);
      if (uint(keys.v[q] & 0xfffffffful) == triangle &&
          (jq == j || (!lens && pairs.v[jq].tau == pairs.v[j].tau))) {
        rep = q;
        done = true;
      }
    }
  Words(A.rep).v[id] = rep;
}

void main() {
  A = ArgsRef(p.args).a;
  const uint k = gl_GlobalInvocationID.y * kRowEntries + gl_GlobalInvocationID.x;
  if (p.stage == TD_IL_REPRESENT || p.stage == TD_IL_COPY) {
    if (k >= p.count) return;
    if (p.stage == TD_IL_REPRESENT) {
      represent(k);
    } else {
      const uint r = Words(A.rep).v[k];
      Out colour = Out(A.colour);
      if (r != k)
        for (uint c = 0u; c < 3u; ++c) colour.v[3u * k + c] = colour.v[3u * r + c];
    }
    return;
  }
  if (p.stage == TD_IL_TRACE) {
    useScene(A.scene);
    traceSample(k);
    return;
  }
  if (p.stage == TD_IL_SHADE) {
    useScene(A.scene);
    if (A.shadowMaps != 0ul) useShadowMaps(A.shadowMaps);
    whitted = WhittedConfig(A.maxDepth, A.importanceCutoff, A.shadowCull, A.whittedFlags);
    shade(k);
    return;
  }
  if (k >= uint(A.width * A.height)) return;
  const int px = int(k % uint(A.width)), py = int(k / uint(A.width));
  if (p.stage == TD_IL_RESOLVE)
    resolvePixel(px, py);
  else
    motionPixel(px, py);
}
