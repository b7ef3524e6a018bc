// A view of the frame: one camera (this frame's, last frame's and the one at shutter close) and
// the viewport it fills in the frame's buffers. A plain render has one view; stereo has two side
// by side (seed 004's dual screen). Pixel (x, y) of a frame-extent buffer belongs to the view
// whose viewport holds it; its camera sees it at (x - view.x, y - view.y).
#pragma once
#include <vector>

#include "scene/camera.h"

namespace tandem {

struct View {
  // This frame's camera, with the frame's sub-pixel jitter (camera.jitter) when a pass asked for
  // it: what rasterized G-buffers and their pixels' rays see.
  Camera camera, prevCamera;
  // The same camera without the jitter, for passes that sample the pixel area themselves (lens
  // rays) and accumulate by jitter-free motion vectors.
  Camera unjitteredCamera;
  Camera shutterCamera;      // when the shutter closes (== camera without motion blur)
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
