// The G-buffer on the GPU (C++ and GLSL): its targets' addresses (shading/gbuffer_layout.h, in
// its order; depth and motion 0 when nothing reads them), and what motion vectors need of a view
// and of the objects (raster/gbuffer.h motionVector).
#ifndef TANDEM_GPU_GBUFFER_ARGS_H
#define TANDEM_GPU_GBUFFER_ARGS_H
#include "camera_data.h"

struct GBufferTargets {
  TD_ADDR depth, position, normal, geoNormal, diffuse, specular, emission, ambient, optical;
  TD_ADDR objectId, materialId, motion;
};

// One view: its jittered camera (the primary rays), the unjittered projections of this frame and
// the last (motion), and depthOf's terms.
struct GpuView {
  GpuCamera camera;
  TD_FLOAT viewProj[16], prevViewProj[16];  // row-major, unjittered
  TD_FLOAT depthOrigin[3], farPlane;        // Camera::depthOf: desc.position, the far plane
  TD_INT cameraMoved, perspective, pad0, pad1;
};

// Per object: whether it moved since last frame and the matrix taking its points back there
// (rows 0-2 of worldToPrev).
struct GpuObjectMotion {
  TD_FLOAT worldToPrev[12];
  TD_UINT moved, pad0, pad1, pad2;
};

struct GBufferArgs {
  TD_ADDR scene, view, targets, motion;  // motion: GpuObjectMotion per object
  TD_INT viewX, viewY, frameWidth, pad;
};

// A pass shading the G-buffer into `hdr` (3 floats a pixel); shadowMaps (a
// GpuShadowMapsHeader, 0: unshadowed) and shadowCull: deferred_shading's map shadows.
struct GBufferShadeArgs {
  TD_ADDR scene, view, targets, hdr;
  TD_INT viewX, viewY, frameWidth, pad;
  TD_ADDR shadowMaps;
  TD_FLOAT shadowCull, pad1;
};
#endif
