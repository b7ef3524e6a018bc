// Arguments of rt_dof.comp (C++ and GLSL): Tan et al. 2022's lens rays in the ray mask's pixels,
// shaded as rt-only shades, split into the near and far fields (passes/dof/rt_dof.h).
#ifndef TANDEM_GPU_RT_DOF_ARGS_H
#define TANDEM_GPU_RT_DOF_ARGS_H
#include "camera_data.h"

// A view: its unjittered camera, projection (row-major; reuse_raster) and viewport.
struct RtDofView {
  GpuCamera camera;
  TD_FLOAT viewProj[16];
  TD_INT x, y, width, height;
};

// After the Whitted counters (TD_COUNT_N): lens rays, and those that took the sharp colour.
#define TD_RT_DOF_LENS_RAYS 0
#define TD_RT_DOF_REUSED 1
#define TD_RT_DOF_COUNTS 2

struct RtDofArgs {
  TD_ADDR scene, views;  // RtDofView[viewCount]
  TD_ADDR mask;          // rays per mask pixel
  TD_ADDR rtNear, rtFar, rtHit, rtFarPosition;
  TD_ADDR sharp, depth;  // reuse_raster: the sharp image and its depth, else 0
  TD_ADDR counters;      // TD_COUNT_N + TD_RT_DOF_COUNTS uints
  TD_ADDR shadowMaps;    // as WhittedArgs
  TD_UINT maskWidth, maskHeight, frameWidth, frameHeight;
  TD_UINT viewCount, seedLo, seedHi, flags;  // flags: TD_WHITTED_*
  TD_FLOAT scale, spread, nearT, lensK;      // lensK: aperture * pixelsPerSlope (ThinLens::coc)
  TD_FLOAT focus, apertureRadius, apertureRotation, importanceCutoff;
  TD_INT apertureBlades, maxDepth;
  TD_FLOAT shadowCull, pad;
};
#endif
