// A Camera as kernels take it (shaders/camera_data.h, shaders/camera.glsl).
#pragma once
#include "gpu/shaders/camera_data.h"
#include "scene/camera.h"

namespace tandem {

// `pixelSpread`: the pixel cone's angle for texture filtering (0: full resolution).
inline GpuCamera gpuCamera(const Camera& c, float pixelSpread) {
  auto put = [](float* out, Vec3 v) { out[0] = v.x, out[1] = v.y, out[2] = v.z; };
  GpuCamera g{};
  put(g.eye, c.eye);
  put(g.forward, c.forward);
  put(g.right, c.right);
  put(g.up, c.upVec);
  put(g.position, c.desc.position);
  g.tanHalfFov = c.tanHalfFov;
  g.aspect = c.aspect;
  g.nearPlane = c.desc.nearPlane;
  g.orthoHalfHeight = c.desc.orthoHeight * 0.5f;
  g.pixelSpread = pixelSpread;
  g.jitter[0] = c.jitter.x, g.jitter[1] = c.jitter.y;
  g.lensSlope[0] = c.lensSlope.x, g.lensSlope[1] = c.lensSlope.y;
  g.width = c.width;
  g.height = c.height;
  g.orthographic = c.desc.projection == Projection::Orthographic ? 1 : 0;
  return g;
}

}  // namespace tandem
