#version 460
// heuristic on the GPU: countObjectPixels (mode TD_HEURISTIC_COUNT), writeMask
// (TD_HEURISTIC_MASK) and a partial object's centralHistogram (TD_HEURISTIC_CENTRAL) of
// HeuristicPass, one invocation a pixel; the selection between them (a few hundred nodes) and the
// cut of the partial object's histogram are the host's.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_GOOGLE_include_directive : require
#include "heuristic_args.h"

layout(local_size_x = 64) in;
layout(push_constant, scalar) uniform Push { HeuristicArgs a; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Floats { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Uints { uint v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Views { HeuristicView v[]; };

// The pixel's squared distance to its view's centre, times four (an integer).
uint64_t distance4(uint i) {
  const uint x = i % a.width, y = i / a.width;
  Views views = Views(a.views);
  uint k = 0u;
  while (k + 1u < a.viewCount && (x < views.v[k].x0 || x >= views.v[k].x1)) ++k;
  const int64_t dx = int64_t(2u * x + 1u) - int64_t(views.v[k].centreX2);
  const int64_t dy = int64_t(2u * y + 1u) - int64_t(views.v[k].centreY2);
  return uint64_t(dx * dx + dy * dy);
}

void main() {
  const uint i = gl_GlobalInvocationID.y * a.rowWidth + gl_GlobalInvocationID.x;
  if (i >= a.pixelCount) return;
  const float id = Floats(a.objectId).v[i];
  const bool shows = id >= 0.0 && uint(id) < a.objectCount;
  if (a.mode == TD_HEURISTIC_COUNT) {
    if (shows) atomicAdd(Uints(a.pixels).v[uint(id)], 1u);
    return;
  }
  const bool partial = shows && uint(id) == a.partialObject;
  if (a.mode == TD_HEURISTIC_CENTRAL) {
    if (partial) {
      const uint64_t bin = distance4(i) * TD_HEURISTIC_BINS / uint64_t(a.norm4);
      atomicAdd(Uints(a.pixels).v[uint(min(bin, uint64_t(TD_HEURISTIC_BINS - 1u)))], 1u);
    }
    return;
  }
  uint bits = shows ? Uints(a.selected).v[uint(id)] : 0u;
  if (partial &&
      distance4(i) * TD_HEURISTIC_BINS < uint64_t(a.partialBins) * uint64_t(a.norm4))
    bits |= a.partialBits;
  Floats mask = Floats(a.mask);
  for (uint k = 0u; k < 3u; ++k) mask.v[3u * i + k] = float((bits >> k) & 1u);
}
