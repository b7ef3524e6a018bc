// The compute rasterizer's records (C++ and GLSL): what raster_triangles.comp, raster_queue.comp
// and raster_resolve.comp take, and a large triangle handed from the first to the second.
#ifndef TANDEM_GPU_RASTER_ARGS_H
#define TANDEM_GPU_RASTER_ARGS_H
#include "camera_data.h"

// Counters the rasterizer adds to (uints), as RasterStats counts them; trianglesIn and the
// triangles of objects outside the frustum are counted on the host.
#define TD_RASTER_CULLED 0
#define TD_RASTER_CLIPPED 1
#define TD_RASTER_BINNED 2
#define TD_RASTER_QUEUED 3
#define TD_RASTER_COUNT_N 4

// A drawn object's triangles: the kernels run over the drawn objects' triangles only, numbered
// one after another (`first`: the object's first), and find each one's object by a binary search.
struct RasterSpan {
  TD_UINT first, object;
};

// One view's draw. The visibility buffer holds a uint64 a pixel: the depth's bits (reversed Z,
// greater is nearer) above the complement of the triangle's index over all objects, so one
// atomicMax keeps the nearest and, between equal depths, the triangle drawn first on the CPU.
struct RasterArgs {
  TD_ADDR scene;          // SceneArgs
  TD_ADDR spans;          // RasterSpan[spanCount]: the objects drawn
  TD_ADDR visibility;     // uint64 per view pixel, cleared to 0 (nothing drawn)
  TD_ADDR queue;          // uint count, 3 uints padding, then queueCapacity RasterTriangles
  TD_ADDR counters;       // TD_RASTER_COUNT_N uints
  TD_FLOAT viewProj[16];  // the jittered camera's, row-major
  GpuCamera camera;       // the pixel rays of alpha-tested texels
  TD_UINT triangles;      // the drawn objects' together
  TD_UINT objectCount, queueCapacity, bothFaces, spanCount;
  TD_FLOAT tau;  // the shutter fraction moving objects are drawn at (GpuObject's time steps)
  // Sample mode (interleaved sampling: Rasterizer::renderSamples) when sampleIds != 0: the
  // visibility buffer is indexed by sample id, and a triangle is tested at the samples of the
  // cells its box touches, the cell's [sampleStart[c], sampleStart[c + 1]) of sampleIds, each at
  // its 8-bit fixed-point position (sampleFixed: x, y) with its depth at samplePos (x, y).
  TD_ADDR sampleStart, sampleIds, sampleFixed, samplePos;
  TD_INT cellW, cellH, cellsX, cellsY;
};

// A set-up triangle (Rasterizer::SetupTriangle) whose pixel box is large: drawn by a workgroup.
struct RasterTriangle {
  TD_INT x[3], y[3];  // 8-bit sub-pixel fixed point, positive orientation
  TD_FLOAT zRef, dzdx, dzdy, xRef, yRef;
  TD_UINT triangle, alphaMask;
  TD_INT px0, px1, py0, py1;  // the pixels whose centres it may cover
  TD_UINT pad;
};

// The resolve of one view's visibility buffer into the G-buffer targets that are non-zero and,
// when hdr is, its shading (vbuffer_shading).
struct RasterResolveArgs {
  TD_ADDR scene, view, targets, motion, visibility, hdr;
  TD_INT viewX, viewY, frameWidth;
  TD_UINT objectCount;
  // Non-zero: shaded towards the camera ray's reverse (ReflectionProbes::draw), else towards the
  // eye (vbuffer_shading).
  TD_INT probe, pad;
};
#endif
