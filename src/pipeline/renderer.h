// The render loop shared by `render`, `bench` and (later) the viewer: evaluates the scene at the
// frame's time, sets up this and last frame's cameras, and runs the pipeline.
#pragma once
#include "pipeline/frame_context.h"
#include "pipeline/pipeline.h"

namespace tandem {

struct RenderSettings {
  int width = 1280, height = 720;  // [1, 16384]
  uint64_t seed = 0;
  float frameRate = 30.0f;  // frame index -> scene time (seconds) = index / frameRate
  float shutter = 0.0f;     // seconds the shutter stays open from the frame time (motion blur)
};

class Renderer {
 public:
  Renderer(const Scene& scene, Pipeline pipeline, RenderSettings settings);

  // Renders frame `index` seen through `camera` (scene time index / frameRate), with an optional
  // sub-pixel jitter in pixels (TAA); motion vectors never include the jitter.
  FrameTimings renderFrame(int index, const CameraDesc& camera, Vec2 jitter = {0, 0});
  // Renders at scene time `time` (seconds); `shutterClose` is the camera when the shutter closes
  // (motion blur over settings.shutter seconds; the same camera for a still one).
  FrameTimings renderFrameAt(int index, float time, const CameraDesc& camera,
                             const CameraDesc& shutterClose, Vec2 jitter = {0, 0});
  const Buffer& output() const { return ctx_.input(pipeline_.output); }
  FrameContext& context() { return ctx_; }
  Pipeline& pipeline() { return pipeline_; }

 private:
  const Scene& scene_;
  Pipeline pipeline_;
  RenderSettings settings_;
  FrameContext ctx_;
  bool first_ = true;
  CameraDesc lastCamera_;
  float lastTime_ = 0;
};

}  // namespace tandem
