// Arguments of interleaved.comp (C++ and GLSL): interleaved sampling (Foster 2015; Fatahalian et
// al. 2009) in stages: each pair's samples (drawn by the compute rasterizer, or traced) shaded, the
// samples resolved to pixels, and each pixel's velocity, view depth and motion.
#ifndef TANDEM_GPU_INTERLEAVED_ARGS_H
#define TANDEM_GPU_INTERLEAVED_ARGS_H
#include "camera_data.h"

#define TD_IL_SHADE 0u      // one pair's samples: visibility (traced, or the raster's), shading
#define TD_IL_RESOLVE 1u    // per pixel: the filter over the samples within reach
#define TD_IL_MOTION 2u     // per pixel: velocity, view_depth (and motion) of its first sample
#define TD_IL_REPRESENT 3u  // shading_rate pixel: each sample's representative
#define TD_IL_COPY 4u       // shading_rate pixel: a sample takes its representative's colour
#define TD_IL_TRACE 5u      // rt with shading_rate pixel: one pair's samples traced into keys

#define TD_IL_WHITTED 1u    // Whitted shading (else local Blinn-Phong without shadows)
#define TD_IL_TIME 2u       // the pairs vary time (motion's carry matrices apply)
#define TD_IL_RASTER 4u     // visibility from the rasterizer (else each sample traced)
#define TD_IL_PER_PIXEL 8u  // shading_rate pixel
#define TD_IL_LENS 16u      // the pairs vary the lens

#define TD_IL_TABLE 1024  // the filter's 1D weight tabulated over [0, radius]

// A pair of T as one view sees it.
struct IlPair {
  GpuCamera camera;  // along the shutter path, at the lens point (cameraForPair)
  TD_FLOAT nowViewProj[16], prevViewProj[16];  // motion: this and last frame's camera into it
  TD_FLOAT tau;
  TD_INT pad[3];
};

// Per pair and animated object (motion): world at the pair's time to world at shutter open,
// close, and the previous frame's same shutter fraction (row-major).
struct IlCarry {
  TD_FLOAT open[16], close[16], prev[16];
};

struct InterleavedArgs {
  TD_ADDR scene, pairs;                  // IlPair[n]
  TD_ADDR carry;                         // IlCarry[n * objectCount] (motion)
  TD_ADDR animated;                      // uint per object (motion)
  TD_ADDR samplePos;                     // per sample: x, y (pixels)
  TD_ADDR samplePair;                    // per sample: its pair (uint)
  TD_ADDR ids;                           // the samples in pair order (uint)
  TD_ADDR mask;                          // sample_mask (frame pixels) or 0
  TD_ADDR colour, position, object;      // per sample: rgb, world point, object (-1: sky)
  TD_ADDR hdr, velocity, depth, motion;  // motion: 0 when nothing reads it
  TD_ADDR weights;                       // float[TD_IL_TABLE + 2]
  TD_ADDR counters;                      // uint[TD_COUNT_N] (whitted_args.h)
  TD_ADDR shadowMaps;                    // 0: none
  TD_ADDR visibility;  // TD_IL_RASTER or _PER_PIXEL: uint64 key per sample (raster_args.h)
  TD_ADDR rep;         // TD_IL_PER_PIXEL: uint per sample
  TD_FLOAT openViewProj[16], closeViewProj[16];  // the view's cameras at shutter open and close
  TD_INT viewX, viewY, width, height;
  TD_INT sx, sy, reach, objectCount;
  TD_UINT frameWidth, flags;
  TD_INT maxDepth;
  TD_UINT whittedFlags;
  TD_FLOAT importanceCutoff, shadowCull, spread, radius;
  TD_FLOAT toTable, pad;
};

struct InterleavedPush {
  TD_ADDR args;
  TD_UINT stage, pair;
  TD_UINT begin, count;  // TD_IL_SHADE: the pair's samples ids[begin .. begin + count); the
                         // sample stages: samples [0, count)
};
#endif
