// Arguments of heuristic.comp (C++ and GLSL): the per-pixel halves of Walewski et al. 2019 §3.2,
// each object's visible area A counted by atomics, and the mask written from the selection the
// host made between the two; with partial objects, the partial object's pixels counted by their
// distance to the view centre, for the host to cut its central part.
#ifndef TANDEM_GPU_HEURISTIC_ARGS_H
#define TANDEM_GPU_HEURISTIC_ARGS_H
#include "shared.h"

#define TD_HEURISTIC_COUNT 0u    // pixels[object] += 1 for each pixel showing it
#define TD_HEURISTIC_MASK 1u     // mask = the effect bits selected[object] of the pixel's object
#define TD_HEURISTIC_CENTRAL 2u  // pixels[bin] += 1 for each pixel of partialObject
#define TD_HEURISTIC_BINS 1024u  // the central histogram's bins (centralHistogram)
#define TD_HEURISTIC_NONE 0xffffffffu

// A view's columns [x0, x1) and twice its centre: a pixel's distance to it, doubled, is an
// integer (x + 0.5 - centre), so the device bins and compares as the host does, exactly.
struct HeuristicView {
  TD_UINT x0, x1, centreX2, centreY2;
};

struct HeuristicArgs {
  TD_ADDR objectId;  // floats, -1 background
  TD_ADDR pixels;    // uint per object (TD_HEURISTIC_CENTRAL: per bin)
  TD_ADDR selected;  // uint per object: effect bits
  TD_ADDR mask;      // 3 floats a pixel
  TD_ADDR views;     // HeuristicView[viewCount], the last covering the whole frame
  TD_UINT pixelCount, objectCount, mode, rowWidth;
  TD_UINT width, viewCount;
  // The partial object (TD_HEURISTIC_NONE: none), the effect bits its part gets, and the part:
  // pixels whose doubled distance d4 has d4 * TD_HEURISTIC_BINS < partialBins * norm4 (norm4:
  // four times the squared half-diagonal of the view holding column 0).
  TD_UINT partialObject, partialBits, partialBins, norm4;
};
#endif
