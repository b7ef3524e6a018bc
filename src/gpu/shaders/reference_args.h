// Arguments of reference.comp (C++ and GLSL): `tandem reference`'s integrators on the GPU, one
// sample per pixel a dispatch added into per-pixel sums the host gathers after each batch.
#ifndef TANDEM_GPU_REFERENCE_ARGS_H
#define TANDEM_GPU_REFERENCE_ARGS_H
#include "camera_data.h"
#include "light_grid_data.h"

#define TD_REFERENCE_PATH 0u
#define TD_REFERENCE_WHITTED 1u
#define TD_REFERENCE_DIFFUSE_GI 2u

// An emissive triangle as an area light (rt/path_tracer.h EmitterTable).
struct GpuEmitter {
  TD_INT object, prim;
  TD_FLOAT pdfArea;  // the density per unit area sample() picks its points with
  TD_FLOAT cdf;      // the table's cumulative weight up to and with it, over the total
};

struct ReferenceArgs {
  TD_ADDR scene, camera;
  TD_ADDR sums;         // 4 floats a pixel: r, g, b, luminance^2 summed over the batch so far
  TD_ADDR emitters;     // GpuEmitter[emitterCount]
  TD_ADDR objectFirst;  // int per object: its first emitter, -1 none
  TD_ADDR lightSkip;    // uint per light: 1 stands in for an emissive mesh (hit instead)
  TD_ADDR counters;     // uint: rays
  TD_UINT integrator, first, cameraMoves, emitterCount;  // first: the sample's index
  TD_UINT seedLo, seedHi;
  TD_INT maxDepth, rouletteDepth;
  TD_FLOAT apertureRadius, focusDistance, apertureRotation;
  TD_INT apertureBlades;
  TD_INT whittedDepth;
  TD_FLOAT importanceCutoff, shadowCull;
  TD_UINT whittedFlags;  // TD_WHITTED_*
  TD_UINT rank;          // this process's rows: stripes of stripeRows with (y / stripeRows) % ranks
  GpuLightGrid grid;     // diffuse-gi: the LightGrid that picks lights (rt/light_grid.h)
  TD_FLOAT pixelSpread;  // the primary hit's texture filtering
  TD_UINT ranks, stripeRows;  // == rank (SampleCluster::ownsRow); 1 process: ranks 1
  TD_FLOAT pad3;
  // cameraMoves: the camera's position and lookAt at shutter close (at open: `camera`'s) and its
  // up vector; each sample's camera lies between them at its shutter time (cameraAtShutter).
  TD_FLOAT openLookAt[3], closePosition[3], closeLookAt[3], cameraUp[3];
};
#endif
