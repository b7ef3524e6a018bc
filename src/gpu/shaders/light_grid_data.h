// The LightGrid on the GPU (C++ and GLSL): rt/light_grid.h's cells, each with the cumulative
// distribution over the candidate lights (x fastest), read by diffuse_gi.glsl. Uniform selection
// is a grid of one cell whose distribution is all zero (LightGrid::pick's fallback: any
// candidate alike).
#ifndef TANDEM_GPU_LIGHT_GRID_DATA_H
#define TANDEM_GPU_LIGHT_GRID_DATA_H
#include "shared.h"

struct GpuLightGrid {
  TD_ADDR cdf, candidates;
  TD_INT dims[3], count;  // count: candidates
  TD_FLOAT lo[3], pad;
  TD_FLOAT invCell[3], pad2;
};
#endif
