// A view's camera on the GPU (C++ and GLSL): Camera::generateRay's cached terms, kept in device
// memory (too many for push constants) and read by camera.glsl.
#ifndef TANDEM_GPU_CAMERA_DATA_H
#define TANDEM_GPU_CAMERA_DATA_H
#include "shared.h"

struct GpuCamera {
  TD_FLOAT eye[3], tanHalfFov;
  TD_FLOAT forward[3], aspect;
  TD_FLOAT right[3], nearPlane;
  TD_FLOAT up[3], orthoHalfHeight;
  TD_FLOAT position[3], pixelSpread;  // orthographic: the view's centre
  TD_FLOAT jitter[2], lensSlope[2];
  TD_INT width, height, orthographic, pad;
};

#endif
