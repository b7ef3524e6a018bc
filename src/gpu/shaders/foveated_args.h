// Arguments of the foveated path tracer's kernels (C++ and GLSL): foveated_pt.comp (the listed
// pixels' paths) and direct_light.comp (every pixel's brightest lights), both reading the
// G-buffer's primary surfaces (primary_surface.glsl).
#ifndef TANDEM_GPU_FOVEATED_ARGS_H
#define TANDEM_GPU_FOVEATED_ARGS_H
#include "camera_data.h"
#include "light_grid_data.h"

// A view (an eye) of the frame: its rectangle, and what PrimarySurfaces reads of its camera.
struct FoveatedView {
  GpuCamera camera;  // the jittered camera: the sky through a pixel's centre
  TD_FLOAT eye[3];   // Camera position (towardsViewer)
  TD_INT orthographic;
  TD_FLOAT forward[3];
  TD_INT x, y, width, height, pad;
};

// A view's rectangle and eye (the image-space passes: nh_denoise, periphery_accumulation).
struct EyeView {
  TD_FLOAT eye[3];
  TD_INT x, y, width, height, pad;
};

// The G-buffer targets PrimarySurfaces reads.
struct GpuPrimarySurfaces {
  TD_ADDR position, normal, geoNormal, diffuse, emission, depth;
};

#define TD_FOVEATED_RAYS 0
#define TD_FOVEATED_SAMPLES 1
#define TD_FOVEATED_COUNTS 2

struct FoveatedPtArgs {
  TD_ADDR scene, views;  // FoveatedView[viewCount]
  GpuPrimarySurfaces g;
  TD_ADDR coords;           // fov_coords: x, y, spp per listed pixel
  TD_ADDR noisy, variance;  // pt_noisy, pt_variance
  TD_ADDR counters;         // uint[TD_FOVEATED_COUNTS]
  GpuLightGrid grid;
  TD_UINT listed, viewCount, frameWidth, seedLo, seedHi, pad;
};

struct DirectLightArgs {
  TD_ADDR scene, views;
  GpuPrimarySurfaces g;
  TD_ADDR direct;       // pt_direct
  TD_ADDR counters;     // uint[TD_FOVEATED_COUNTS]
  GpuLightGrid lights;  // the candidates (the scene's sampled lights)
  TD_INT count;         // lights traced per pixel
  TD_UINT viewCount, frameWidth, pad;
};
// periphery_accumulation.comp's counters: the history lengths summed (in units of 2^-16, 64-bit
// integer atomics: an exact, ordered sum) and the pixels summed.
struct PeripheryCounters {
  TD_ADDR framesSum, pixels;
};

#define TD_PERIPHERY_DEMODULATE 1u
#define TD_PERIPHERY_FILL 2u

struct PeripheryArgs {
  TD_ADDR views;  // EyeView[viewCount]
  TD_ADDR noisy, mask, layer, motion, position, normal, depth, diffuse, emission;
  TD_ADDR variance, previous;  // 0: absent (no variance input; no history: reset)
  TD_ADDR accum, accumVariance, accumMask, history;
  TD_ADDR counters;  // PeripheryCounters
  TD_UINT width, viewCount, flags;
  TD_INT fromLayer;
  TD_FLOAT alphaMin, positionTolerance, minCos, pad;
};
#endif
