// The TAA kernel's arguments (C++ and GLSL): passes/baselines/taa.cpp on the GPU.
#ifndef TANDEM_GPU_TAA_ARGS_H
#define TANDEM_GPU_TAA_ARGS_H
#include "shared.h"
struct TaaArgs {
  TD_ADDR current;  // hdr, 3 floats a pixel
  TD_ADDR motion;   // 2 floats a pixel
  TD_ADDR history;  // last frame's taa, 3 floats a pixel (0: none, the current frame is taken)
  TD_ADDR result;   // taa, 3 floats a pixel
  TD_UINT width, height;          // the frame
  TD_UINT viewWidth, viewHeight;  // each view (eyes side by side)
  TD_FLOAT alpha, motionAlpha, invMotionPixels;
  TD_UINT clampHistory, catmullRom, pad;
};
#endif
