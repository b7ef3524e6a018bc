// Arguments of accumulation.comp (C++ and GLSL): the accumulation baseline's one pair (a full
// frame rasterized at one time and lens point by the compute rasterizer) shaded and added into
// hdr with the pair's weight.
#ifndef TANDEM_GPU_ACCUMULATION_ARGS_H
#define TANDEM_GPU_ACCUMULATION_ARGS_H
#include "camera_data.h"

struct AccumulationArgs {
  TD_ADDR scene, camera;  // the pair's camera (GpuCamera)
  TD_ADDR visibility;     // uint64 per view pixel (raster_args.h)
  TD_ADDR hdr;
  TD_ADDR counters;  // uint: rays
  TD_INT viewX, viewY;
  TD_UINT frameWidth, objectCount;
  TD_UINT whittedShading;
  TD_FLOAT weight;  // 1 / samples
  TD_INT maxDepth;
  TD_UINT whittedFlags;
  TD_FLOAT importanceCutoff, shadowCull;
  TD_FLOAT tau;  // the pair's shutter fraction: where moving objects are
};
#endif
