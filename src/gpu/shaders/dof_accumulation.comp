#version 460
// dof_accumulation on the GPU, one invocation a mask pixel, as DofAccumulationPass::execute (Tan
// et al. 2022 §3.2.3): the near history reprojected by the motion vector, the far history by the
// rays' mean far hit (else the 3x3 neighbourhood's) seen by last frame's camera; the moving
// averages (adaptive by the temporal gradient), the merge by the hit ratio, the luminance moments
// and the variance of the accumulated mean (blurred afterwards by convolve.comp).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "dof_args.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { uint64_t args; };
layout(buffer_reference, scalar, buffer_reference_align = 8) readonly buffer ArgsRef {
  DofAccumulationArgs a;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Views {
  DofAccumulationView v[];
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Floats { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Counters {
  uint64_t varianceSum;  // in units of 2^-32 (64-bit integer atomics: an exact, ordered sum)
  uint64_t above;
};

DofAccumulationArgs A;

#include "color.glsl"
float saturate(float x) { return clamp(x, 0.0, 1.0); }

// history(): a bilinear sample (sampleBilinear, floor) of a w x h buffer of C channels; false
// outside it (or with none).
bool history(uint64_t b, uint C, float x, float y, out float s[5]) {
  for (uint c = 0u; c < 5u; ++c) s[c] = 0.0;
  const int w = int(A.width), h = int(A.height);
  if (b == 0ul || x < 0.0 || y < 0.0 || x > float(w) || y > float(h)) return false;
  Floats f = Floats(b);
  precise const float fx = x - 0.5, fy = y - 0.5;
  const int x0 = int(floor(fx)), y0 = int(floor(fy));
  precise const float tx = fx - float(x0), ty = fy - float(y0);
  const int xa = clamp(x0, 0, w - 1), xb = clamp(x0 + 1, 0, w - 1);
  const int ya = clamp(y0, 0, h - 1), yb = clamp(y0 + 1, 0, h - 1);
  for (uint c = 0u; c < C; ++c) {
    const float p00 = f.v[C * uint(ya * w + xa) + c], p10 = f.v[C * uint(ya * w + xb) + c];
    const float p01 = f.v[C * uint(yb * w + xa) + c], p11 = f.v[C * uint(yb * w + xb) + c];
    precise const float r =
        (p00 * (1.0 - tx) + p10 * tx) * (1.0 - ty) + (p01 * (1.0 - tx) + p11 * tx) * ty;
    s[c] = r;
  }
  return true;
}

vec3 rgb(uint64_t b, uint C, int x, int y) {
  Floats f = Floats(b);
  const uint o = C * uint(y * int(A.width) + x);
  return vec3(f.v[o], f.v[o + 1u], f.v[o + 2u]);
}

// reprojectFar: where the far field was last frame (unchanged when no ray saw one).
void reprojectFar(int x, int y, DofAccumulationView view, inout float fxp, inout float fyp) {
  Floats fp = Floats(A.rtFarPosition);
  const int w = int(A.width), h = int(A.height);
  precise vec3 farP = vec3(0.0);
  precise float farW = 0.0;
  if (fp.v[4u * uint(y * w + x) + 3u] > 0.0) {
    farP = rgb(A.rtFarPosition, 4u, x, y);
    farW = 1.0;
  } else {
    for (int j = max(y - 1, 0); j <= min(y + 1, h - 1); ++j)
      for (int i = max(x - 1, 0); i <= min(x + 1, w - 1); ++i)
        if (fp.v[4u * uint(j * w + i) + 3u] > 0.0) {
          farP = farP + rgb(A.rtFarPosition, 4u, i, j);
          farW += 1.0;
        }
    if (farW > 0.0) farP = farP * (1.0 / farW);
  }
  if (farW <= 0.0) return;
  // Camera::project through last frame's camera.
  const float m[16] = view.prevViewProj;
  precise const float cx = m[0] * farP.x + m[1] * farP.y + m[2] * farP.z + m[3];
  precise const float cy = m[4] * farP.x + m[5] * farP.y + m[6] * farP.z + m[7];
  precise const float cw = m[12] * farP.x + m[13] * farP.y + m[14] * farP.z + m[15];
  if (view.perspective != 0 && cw <= 1e-8) return;
  precise const float iw = 1.0 / cw;
  precise const float px = (cx * iw * 0.5 + 0.5) * float(view.width);
  precise const float py = (0.5 - cy * iw * 0.5) * float(view.height);
  fxp = (px + float(view.x)) / A.scale;  // the view's pixel -> the frame's
  fyp = (py + float(view.y)) / A.scale;
}

void main() {
  A = ArgsRef(args).a;
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= int(A.width) || y >= int(A.height)) return;
  const uint i = uint(y) * A.width + uint(x);
  precise const float fx = (float(x) + 0.5) * A.scale, fy = (float(y) + 0.5) * A.scale;
  // viewAt: the first view holding the pixel, else the first.
  const int vx = min(int(fx), int(A.frameWidth) - 1), vy = min(int(fy), int(A.frameHeight) - 1);
  uint vi = 0u;
  for (uint k = A.viewCount; k-- > 0u;) {
    const DofAccumulationView v = Views(A.views).v[k];
    if (vx >= v.x && vy >= v.y && vx < v.x + v.width && vy < v.y + v.height) vi = k;
  }
  const DofAccumulationView view = Views(A.views).v[vi];
  Floats motion = Floats(A.motion);
  const uint mi = 2u * (uint(min(int(fy), int(A.motionHeight) - 1)) * A.motionWidth +
                        uint(min(int(fx), int(A.motionWidth) - 1)));
  const vec2 mv = vec2(motion.v[mi], motion.v[mi + 1u]);
  precise const float nx = (fx - mv.x) / A.scale, ny = (fy - mv.y) / A.scale;
  float fxp = nx, fyp = ny;
  reprojectFar(x, y, view, fxp, fyp);
  // dof::AccChannels: rgb 0, share 3, coc 4; MomentChannels: mean 0, mean square 1, frames 2.
  float hn[5], hf[5], hm[5];
  const bool nearOk = history(A.prevNear, 5u, nx, ny, hn);
  const bool haveNear = nearOk && history(A.prevMoments, 3u, nx, ny, hm);
  if (!nearOk) history(0ul, 3u, 0.0, 0.0, hm);  // zeroes
  const bool haveFar = history(A.prevFar, 5u, fxp, fyp, hf);
  const bool haveHistory = haveNear && haveFar;

  Floats hit = Floats(A.rtHit);
  const float rays = hit.v[2u * i + 1u], hc = hit.v[2u * i];
  const vec3 cn = rgb(A.rtNear, 4u, x, y), cf = rgb(A.rtFar, 4u, x, y);
  const float cnCoc = Floats(A.rtNear).v[4u * i + 3u], cfCoc = Floats(A.rtFar).v[4u * i + 3u];
  precise const vec3 merged = cf + (cn - cf) * hc;
  const float lum = luminance(merged);
  float age = haveHistory ? hm[2] : 0.0;
  precise float alpha = rays > 0.0 ? max(A.minAlpha, 1.0 / (age + 1.0)) : 0.0;
  if (!haveHistory) {
    for (uint c = 0u; c < 5u; ++c) hn[c] = hf[c] = hm[c] = 0.0;
    age = 0.0;
    alpha = rays > 0.0 ? 1.0 : 0.0;
  } else if (A.adaptive != 0u && rays > 0.0) {
    // adaptiveAlpha: the temporal gradient beyond two standard deviations raises the weight.
    precise const float hsum = hn[3] + hf[3];
    const float histLum =
        hsum > 0.0 ? luminance(vec3(hn[0], hn[1], hn[2]) + vec3(hf[0], hf[1], hf[2])) / hsum : lum;
    precise const float sigma = sqrt(max(hm[1] - hm[0] * hm[0], 0.0));
    precise const float lambda =
        saturate((abs(lum - histLum) - 2.0 * sigma) / max(max(lum, histLum), 1e-3));
    alpha = alpha + (1.0 - alpha) * lambda;
  }
  // premultiplied(): a layer's colour and CoC by its share of the rays.
  const float curNear[5] = float[5](hc * cn.x, hc * cn.y, hc * cn.z, hc, hc * cnCoc);
  const float farShare = 1.0 - hc;
  const float curFar[5] =
      float[5](farShare * cf.x, farShare * cf.y, farShare * cf.z, farShare, farShare * cfCoc);
  float an[5], af[5];
  Floats accNear = Floats(A.accNear), accFar = Floats(A.accFar), moments = Floats(A.accMoments);
  for (uint c = 0u; c < 5u; ++c) {
    precise const float n = hn[c] + (curNear[c] - hn[c]) * alpha;
    precise const float f = hf[c] + (curFar[c] - hf[c]) * alpha;
    an[c] = n;
    af[c] = f;
    accNear.v[5u * i + c] = n;
    accFar.v[5u * i + c] = f;
  }
  const float H = an[3], F = af[3];
  precise const float total = H + F;
  Floats color = Floats(A.rtColor);
  moments.v[3u * i + 2u] = min(age + (rays > 0.0 ? 1.0 : 0.0), 1000.0);
  float variance = 0.0;
  if (total <= 1e-6) {
    for (uint c = 0u; c < 9u; ++c) color.v[9u * i + c] = 0.0;
    moments.v[3u * i] = 0.0;
    moments.v[3u * i + 1u] = 0.0;
  } else {
    const bool moving = view.cameraMoved != 0 ||
                        mv.x * mv.x + mv.y * mv.y > A.motionPixels * A.motionPixels;
    precise float hr = H / total;
    if (moving && rays > 0.0) hr = hc;
    precise const vec3 nearC = H > 1e-6 ? vec3(an[0], an[1], an[2]) * (1.0 / H) : vec3(0.0);
    precise const vec3 farC = F > 1e-6 ? vec3(af[0], af[1], af[2]) * (1.0 / F) : vec3(0.0);
    precise const float nearCoc = H > 1e-6 ? an[4] / H : 0.0;
    precise const float farCoc = F > 1e-6 ? af[4] / F : 0.0;
    if (H <= 1e-6) hr = 0.0;
    if (F <= 1e-6) hr = 1.0;
    precise const vec3 c = farC + (nearC - farC) * hr;
    color.v[9u * i] = c.x;
    color.v[9u * i + 1u] = c.y;
    color.v[9u * i + 2u] = c.z;
    float mean, meanSquare;
    if (rays > 0.0) {
      precise const float m0 = hm[0] + (lum - hm[0]) * alpha;
      precise const float m1 = hm[1] + (lum * lum - hm[1]) * alpha;
      mean = m0;
      meanSquare = m1;
    } else {
      mean = hm[0];
      meanSquare = hm[1];
    }
    moments.v[3u * i] = mean;
    moments.v[3u * i + 1u] = meanSquare;
    const float frames =
        min(max(moments.v[3u * i + 2u], 1.0), (2.0 - A.minAlpha) / A.minAlpha);
    precise const float v = max(meanSquare - mean * mean, 0.0) / frames;
    variance = v;
    precise const float coc = farCoc + (nearCoc - farCoc) * hr;
    color.v[9u * i + 3u] = coc;
    color.v[9u * i + 4u] = hr;
    color.v[9u * i + 5u] = 1.0;
    color.v[9u * i + 6u] = nearC.x;
    color.v[9u * i + 7u] = nearC.y;
    color.v[9u * i + 8u] = nearC.z;
  }
  Floats(A.variance).v[i] = variance;
  if (variance > 0.0)
    atomicAdd(Counters(A.counters).varianceSum, uint64_t(min(variance, 1e6) * 4294967296.0));
  if (variance > 1e-6) atomicAdd(Counters(A.counters).above, 1ul);
}
