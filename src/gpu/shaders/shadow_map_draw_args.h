// Drawing the shadow maps on the GPU (C++ and GLSL): the conservative maps, as
// drawConservativeDepth draws them (raster/conservative_depth.cpp), and the texels kept beside each
// map (its static copy, the opaque casters' depth). The depth maps themselves are drawn by the
// compute rasterizer (raster_args.h).
#ifndef TANDEM_GPU_SHADOW_MAP_DRAW_ARGS_H
#define TANDEM_GPU_SHADOW_MAP_DRAW_ARGS_H
#include "shared.h"

#define TD_CONSERVATIVE_SETUP 0  // a thread a triangle: small ones drawn, large ones queued
#define TD_CONSERVATIVE_QUEUE 1  // a workgroup a queued triangle

// One face's conservative map: the triangles of the objects the spans name (raster_args.h), then
// `boxTriangles` world-space triangles (the boxes of objects swept over an open shutter).
struct ConservativeArgs {
  TD_ADDR scene;          // SceneArgs
  TD_ADDR spans;          // RasterSpan[spanCount]
  TD_ADDR boxes;          // ConservativeWorldTriangle[boxTriangles]
  TD_ADDR near;           // uint64 per texel: depth bits over the object's complement (atomicMax)
  TD_ADDR queue;          // uint count, 3 uints padding, then queueCapacity ConservativeTriangles
  TD_FLOAT viewProj[16];  // the face camera's, row-major
  TD_FLOAT eye[3], nearPlane;
  TD_FLOAT forward[3], farPlane;
  TD_INT width, height, perspective;
  TD_UINT triangles;  // the spans' together
  TD_UINT objectCount, boxTriangles, queueCapacity, phase, spanCount, pad;
};

struct ConservativeWorldTriangle {
  TD_FLOAT a[3], b[3], c[3];
  TD_UINT object;
};

// A projected triangle (texel coordinates and reversed-Z depth) whose texel box is large.
struct ConservativeTriangle {
  TD_FLOAT a[3], b[3], c[3];
  TD_UINT object;
  TD_INT x0, y0, x1, y1;  // its texel box, inclusive
};

#define TD_TEXELS_RESTORE 1  // the static copy back into the maps
#define TD_TEXELS_OPAQUE 2   // opaque[k]: the map's depth where an opaque caster drew it, else 0

// A rectangle [x0, x1) x [y0, y1) of one face's texels.
struct ShadowTexelArgs {
  TD_ADDR scene;
  TD_ADDR depth, near;              // the maps (uint64 per texel)
  TD_ADDR staticDepth, staticNear;  // their static casters' copy (TD_TEXELS_RESTORE)
  TD_ADDR opaque;                   // float per texel (TD_TEXELS_OPAQUE)
  TD_ADDR opaqueCasters;            // uint per object: an opaque caster
  TD_INT width, x0, y0, x1, y1;
  TD_UINT mode, objectCount, pad;
};
#endif
