// Arguments of downsample.comp (C++ and GLSL): one reduction of a colour buffer, by 2x2 boxes
// (downsampleBox) or bilinear samples at the smaller image's pixel centres (resizeBilinear).
#ifndef TANDEM_GPU_DOWNSAMPLE_ARGS_H
#define TANDEM_GPU_DOWNSAMPLE_ARGS_H
#include "shared.h"

#define TD_DOWNSAMPLE_BOX 0u
#define TD_DOWNSAMPLE_BILINEAR 1u

struct DownsampleArgs {
  TD_ADDR src, dst;
  TD_INT srcWidth, srcHeight, dstWidth, dstHeight;
  TD_UINT channels, mode;  // mode: TD_DOWNSAMPLE_* (`filter` is reserved in GLSL)
};
#endif
