// Screen-space motion of the surfaces that stood still while the camera moved: each pixel's
// G-buffer position reprojected through last frame's camera, 8 or 16 pixels at a time (a
// Highway kernel), bit for bit what motionVectorAtPixel gives them (the file is built without
// FMA contraction). The raster G-buffer runs it over each tile after the resolve, which then
// computes motion one pixel at a time only for objects that moved.
#pragma once
#include "scene/view.h"

namespace tandem {

struct CameraMotionTile {
  const float* position;  // 3 floats a pixel
  const float* objectId;  // 1 float a pixel, -1 background
  float* motion;          // 2 floats a pixel
  int stride;             // pixels per row of the three buffers
  int x0, y0, x1, y1;     // frame pixels, [x0, x1) x [y0, y1)
};

// Writes the motion of every pixel [x0, x1) x [y0, y1) whose object id o >= 0 has
// moved[o] == 0; other pixels are left as they are. `view` gives the pixel centres (view-local)
// and last frame's camera.
void writeCameraMotion(const CameraMotionTile& tile, const View& view, const float* moved,
                       int objects);

}  // namespace tandem
