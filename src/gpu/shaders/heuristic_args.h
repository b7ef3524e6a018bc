// Arguments of heuristic.comp (C++ and GLSL): the per-pixel halves of Walewski et al. 2019 §3.2,
// each object's visible area A counted by atomics, and the mask written from the selection the
// host made between the two.
#ifndef TANDEM_GPU_HEURISTIC_ARGS_H
#define TANDEM_GPU_HEURISTIC_ARGS_H
#include "shared.h"

#define TD_HEURISTIC_COUNT 0u  // pixels[object] += 1 for each pixel showing it
#define TD_HEURISTIC_MASK 1u   // mask = the effect bits selected[object] of the pixel's object

struct HeuristicArgs {
  TD_ADDR objectId;  // floats, -1 background
  TD_ADDR pixels;    // uint per object
  TD_ADDR selected;  // uint per object: effect bits
  TD_ADDR mask;      // 3 floats a pixel
  TD_UINT pixelCount, objectCount, mode, rowWidth;
};
#endif
