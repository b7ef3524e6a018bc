// Reference images on demand: rendered by the progressive path tracer, or loaded from a cache
// folder where an identical request (scene content, camera, time, shutter, resolution and
// settings, hashed) was rendered before. Experiments and `tandem reference` share it.
#pragma once
#include <memory>
#include <string>

#include "core/buffer.h"
#include "gpu/gpu_device.h"
#include "rt/reference_render.h"
#include "scene/scene.h"

namespace tandem {

struct ReferenceJob {
  const Scene* scene = nullptr;
  CameraDesc camera, shutterCamera;  // at shutter open and close (the same: a still camera)
  float time = 0, shutter = 0;       // scene time and shutter length, seconds
  int width = 640, height = 360;     // one eye in stereo
  StereoDesc stereo;                 // enabled: both eyes side by side
  ReferenceSettings settings;
  // The device it renders on (null: the CPU). Not part of the key: both devices take the same
  // samples of the same estimator.
  std::shared_ptr<GpuDevice> gpu;
};

struct ReferenceImage {
  Buffer hdr, variance;
  int spp = 0;
  double seconds = 0, relativeError = 0;  // seconds: the whole render (scene, BVH, sampling)
  double samplingSeconds = 0;             // path tracing alone
  uint64_t rays = 0;
  bool fromCache = false;
  std::string key;
};

// Bump when the path tracer's estimate changes meaning, so stale cache entries are not reused.
constexpr int kReferenceVersion = 2;

std::string referenceKey(const ReferenceJob& job);
// Renders the job (split across `cluster`'s processes: every rank must call it; only rank 0
// gets the image and writes the cache), or loads it from `cacheDir` (empty: no cache).
ReferenceImage referenceImage(const ReferenceJob& job, const std::string& cacheDir,
                              SampleCluster* cluster = nullptr);

}  // namespace tandem
