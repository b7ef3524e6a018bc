// Everything one frame's passes share: the evaluated scene, camera (and last frame's), the ray
// tracer, named buffers, and per-pass timings/counters.
#pragma once
#include <array>
#include <map>
#include <memory>
#include <string>

#include "core/buffer.h"
#include "core/error.h"
#include "core/profiler.h"
#include "raster/rasterizer.h"
#include "rt/ray_tracer.h"
#include "scene/camera.h"
#include "scene/frame_scene.h"

namespace tandem {

// Secondary effects the hybrid pipeline can ray trace per object (the heuristic mask's channels).
enum Effect : int { kShadow = 0, kReflection = 1, kRefraction = 2 };
constexpr int kEffectCount = 3;

// What the last rt_secondary pass measured, fed back to the next frame's heuristic (the ms budget
// prices nodes from cpuMs and calibrates against `ms`; recursion-aware costs use rays per pixel).
struct RtStats {
  int64_t serial = -1;  // FrameContext::serial of the frame measured; -1 before any RT pass ran
  bool timeEffects = false;  // asked for by the heuristic (ms budget): fills cpuMs
  double ms = 0;             // wall time of the pass
  std::vector<std::array<uint64_t, kEffectCount>> pixels, rays;  // per object, per effect
  std::vector<std::array<double, kEffectCount>> cpuMs;  // thread time per object and effect
                                                        // (timing costs ~8 %, so only on request)
};

class SampleCluster;

struct FrameContext {
  const Scene* scene = nullptr;
  FrameScene frame;
  Camera camera, prevCamera;
  Camera shutterCamera;      // the camera when the shutter closes (== camera without motion blur)
  bool cameraMoved = false;  // this frame's unjittered view-projection differs from last frame's
  int width = 0, height = 0;
  int frameIndex = 0;
  int64_t serial = -1;  // counts executed frames (frameIndex may repeat, e.g. a static shot)
  uint64_t seed = 0;
  std::map<std::string, Buffer> buffers;
  Rasterizer rasterizer;        // owns binning scratch reused across frames
  VisibilityBuffer visibility;  // last raster result (also shown as AOVs)
  RasterStats rasterStats;      // triangles in / culled / clipped / binned by the last raster pass
  double passRays = 0;          // a pass adds the rays it traced; the pipeline records it
  std::vector<PassTiming> passParts;  // optional sub-timings a pass reports ("pass/part")
  RtStats rtStats;                    // the latest rt_secondary measurements
  int samplesPerPixel = 0;            // progressive passes: samples reached in the last frame
  SampleCluster* cluster = nullptr;   // distributed (MPI) reference rendering; null: one process

  // The ray tracer, (re)built for the current frame's geometry on first use in a frame.
  RayTracer& rayTracer();
  // A buffer of the given shape, created or reshaped (contents kept when the shape matches).
  Buffer& output(const std::string& name, int channels);
  const Buffer& input(const std::string& name) const;

 private:
  std::unique_ptr<RayTracer> rt_;
};

}  // namespace tandem
