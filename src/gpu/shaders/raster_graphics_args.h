// Arguments of the graphics pipeline's visibility draw (raster_graphics.vert / .frag, C++ and
// GLSL): one draw an object, its triangles pulled from the scene by gl_VertexIndex, and the pack
// of its attachments into the compute rasterizer's visibility keys (raster_pack.comp).
#ifndef TANDEM_GPU_RASTER_GRAPHICS_ARGS_H
#define TANDEM_GPU_RASTER_GRAPHICS_ARGS_H
#include "shared.h"

struct RasterDrawArgs {
  TD_ADDR scene;          // SceneArgs
  TD_ADDR camera;         // GpuCamera: the pixel rays of alpha-tested texels
  TD_FLOAT viewProj[16];  // the jittered camera's, row-major
  TD_UINT object;
  TD_FLOAT tau;  // the shutter fraction moving objects are drawn at
};

// ids: a uint a pixel (0: nothing drawn, else the triangle's index + 1); depths: the depth
// attachment's floats; visibility: the keys raster_resolve reads (raster_args.h).
struct RasterPackArgs {
  TD_ADDR ids, depths, visibility;
  TD_UINT pixels, pad;
};
#endif
