// Arguments of postfx_motion_blur.comp (C++ and GLSL): McGuire et al. 2012's post-process motion
// blur in stages over one view (TileMax, NeighborMax with the mask of mixed motion, the gather),
// and the hybrid's composite (mb_composite).
#ifndef TANDEM_GPU_MOTION_BLUR_ARGS_H
#define TANDEM_GPU_MOTION_BLUR_ARGS_H
#include "shared.h"

#define TD_MB_TILES 0u       // per tile: largest radius, smallest speed, velocity jump
#define TD_MB_NEIGHBOURS 1u  // per tile: the 3 x 3 tiles' largest radius, the mask
#define TD_MB_GATHER 2u      // per pixel: the gather and the mask's value
#define TD_MB_COMPOSITE 3u   // per frame pixel: mb_composite

// Floats a tile: TileMax (x, y), smallest speed, edge (0/1), NeighborMax (x, y), mask.
#define TD_MB_TILE_FLOATS 7

struct MotionBlurArgs {
  TD_ADDR colour, velocity, depth;  // hdr, velocity, view_depth
  TD_ADDR postfx, mask;             // mb_postfx, mb_mask
  TD_ADDR interleaved, composite;   // mb_composite: mb_interleaved in, hdr out
  TD_ADDR tiles;                    // float[TD_MB_TILE_FLOATS] per tile, the view's
  TD_ADDR masked;                   // uint: masked tiles (summed over views)
  TD_UINT frameWidth, frameHeight;
  TD_INT ox, oy, width, height;  // the view
  TD_INT K, S, tilesX, tilesY;
  TD_FLOAT softZ, threshold;
  TD_UINT edgesOnly, pad;
};
#endif
