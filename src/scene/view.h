// A view of the frame: one camera (this frame's, last frame's and the one at shutter close) and
// the viewport it fills in the frame's buffers. A plain render has one view; stereo has two side
// by side (Peres 2022's dual screen). Pixel (x, y) of a frame-extent buffer belongs to the view
// whose viewport holds it; its camera sees it at (x - view.x, y - view.y).
#pragma once
#include <vector>

#include "scene/camera.h"

namespace tandem {

struct View {
  // This frame's camera, last frame's, and the one when the shutter closes (== camera without
  // motion blur); none of them jittered.
  Camera camera, prevCamera, shutterCamera;
  // This frame's sub-pixel projection jitter in pixels (0 unless a pass asked for it,
  // FrameRequest).
  Vec2 jitter{0, 0};
  // `camera` shifted by `jitter`: the pixel grid's primary visibility. The passes that rasterize
  // or trace the grid's primary rays (the raster and RT G-buffers, rt_whitted) and those that
  // rebuild a G-buffer pixel's ray or project into its image (the shading passes, rt_secondary,
  // ss_fallback, foveated_pt) use it, so all of them see the same sub-pixel positions. Passes
  // that sample the pixel area themselves (lens rays, the path-traced reference, interleaved
  // samples) use `camera` and add `jitter` only where they want it.
  Camera jitteredCamera;
  int x = 0, y = 0;          // viewport origin; its size is the camera's
  bool cameraMoved = false;  // unjittered view-projection differs from last frame's
  int width() const { return camera.width; }
  int height() const { return camera.height; }
  bool contains(int px, int py) const {
    return px >= x && py >= y && px < x + camera.width && py < y + camera.height;
  }
};

// The view holding frame pixel (x, y) (the first view when none does).
inline const View& viewAt(const std::vector<View>& views, int x, int y) {
  for (const View& v : views)
    if (v.contains(x, y)) return v;
  return views.front();
}

}  // namespace tandem
