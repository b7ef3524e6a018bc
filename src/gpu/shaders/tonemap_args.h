// The tonemap kernel's arguments (C++ and GLSL).
#ifndef TANDEM_GPU_TONEMAP_ARGS_H
#define TANDEM_GPU_TONEMAP_ARGS_H
#include "shared.h"
struct TonemapArgs {
  TD_ADDR hdr;       // count floats: linear radiance
  TD_ADDR display;   // count floats: display sRGB in [0, 1]
  TD_UINT count;     // values (3 per pixel)
  TD_FLOAT scale;    // 2^exposure
  TD_UINT op;        // ToneOperator: 0 clamp, 1 reinhard, 2 aces
  TD_UINT rowWidth;  // values per dispatch row (2D grid: x groups * 64)
};
#endif
