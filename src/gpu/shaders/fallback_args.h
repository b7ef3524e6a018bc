// Arguments of fallback.comp (C++ and GLSL): ss_fallback's inputs, its output, the frame's shadow
// maps and reflection probes on the device, and its settings.
#ifndef TANDEM_GPU_FALLBACK_ARGS_H
#define TANDEM_GPU_FALLBACK_ARGS_H
#include "shared.h"

// What the kernel does: count each object's pixels that show an untraced reflection or
// refraction and its reflective or transparent pixels (the probes' areas), or write the fallback
// buffer.
#define TD_FALLBACK_COUNT 0
#define TD_FALLBACK_WRITE 1
// FallbackSettings::Mode
#define TD_FALLBACK_OFF 0
#define TD_FALLBACK_ENVIRONMENT 1
#define TD_FALLBACK_SCREEN_SPACE 2
#define TD_FALLBACK_PROBE 3

// Per view: the march's jittered projection, and the scene's box (the probes' parallax proxy).
struct FallbackView {
  TD_FLOAT viewProj[16];         // row-major, the jittered camera's
  TD_FLOAT boundsLo[3], reach;   // reach: the longest march (the scene's diagonal)
  TD_FLOAT boundsHi[3], growth;  // growth: the march's geometric step
};

// Reflection probes: per object a record (size 0: none).
struct GpuProbe {
  TD_FLOAT viewProj[6][16];  // the six faces' cameras, row-major
  TD_FLOAT centre[3], radius;
  TD_INT size, pad;
  TD_ADDR faces;  // six size x size RGB float faces one after another
};

struct FallbackArgs {
  TD_ADDR scene, view, march, sources;  // view: GpuView; march: FallbackView; sources: G-buffer
  TD_ADDR hdr, mask, result;  // mask: heuristic_mask; result: the 11-channel fallback buffer
  TD_ADDR shadowMaps;         // GpuShadowMapsHeader, 0 without shadow-map shadows
  TD_ADDR probes;             // GpuProbe per object (mode probe)
  TD_ADDR areas;              // 2 x objects uints: untraced, then all (TD_FALLBACK_COUNT)
  TD_INT viewX, viewY, frameWidth, phase;
  TD_INT mode, steps;
  TD_FLOAT thickness, shadowCull;
  TD_UINT objectCount, pad;
};
#endif
