// The frame's raster shadow maps on the GPU (C++ and GLSL): a header, a record per light and per
// map face, each face's texels (raster/shadow_maps.h; drawn by shadow_map_draw.comp and the
// compute rasterizer, read by shadow_maps.glsl as ShadowMaps::classify and visibility read them).
#ifndef TANDEM_GPU_SHADOW_MAPS_DATA_H
#define TANDEM_GPU_SHADOW_MAPS_DATA_H
#include "shared.h"

struct GpuShadowMapsHeader {
  TD_ADDR lights, faces;  // GpuShadowLight[lightCount], GpuShadowFace[]
  TD_UINT lightCount, pad;
};

struct GpuShadowLight {
  TD_INT firstFace, faceCount;  // faceCount 0: no maps (6: a cube, chosen by the major axis)
  TD_INT casts, pad;            // the light casts shadows
};

struct GpuShadowFace {
  TD_FLOAT viewProj[16];  // row-major
  TD_FLOAT eye[3], texelPerDistance;
  TD_FLOAT forward[3], nearPlane;
  TD_FLOAT farPlane;
  TD_INT width, height, perspective;
  // width x height uint64 each, a depth's bits (reversed Z) over a complement: as the compute
  // rasterizer draws them (raster_args.h), so one atomicMax keeps the nearest.
  TD_ADDR depth;   // the map: over the drawn triangle's index
  TD_ADDR near;    // the conservative map: over the object's index (0: nothing touched)
  TD_ADDR opaque;  // width x height floats: depth of opaque static casters, else 0
};
#endif
