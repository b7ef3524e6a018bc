// The render loop shared by `render`, `bench`, the experiments and the viewer: evaluates the scene
// at the frame's time, sets up the views (one camera, or two eyes side by side for stereo) with
// this and last frame's cameras and any jitter a pass asked for, fires history resets, and runs
// the pipeline.
#pragma once
#include <string>

#include "core/low_discrepancy.h"
#include "gpu/gpu_device.h"
#include "pipeline/frame_context.h"
#include "pipeline/pipeline.h"

namespace tandem {

struct RenderSettings {
  int width = 1280, height = 720;  // one view (one eye in stereo), [1, 16384]
  uint64_t seed = 0;
  float frameRate = 30.0f;  // frame index -> scene time (seconds) = index / frameRate
  float shutter = 0.0f;     // seconds the shutter stays open from the frame time (motion blur)
  StereoDesc stereo{};      // enabled: two eyes side by side, the frame 2 x width wide
  // Scales the pixel cone that picks texture levels of detail: a supersampled render of n x n
  // samples per pixel uses 1 / n, so each sample filters only its share of the pixel.
  float textureFootprint = 1.0f;
  // The GPU the passes that have a GPU version run on (GpuDevice::forChoice); null: the CPU.
  std::shared_ptr<GpuDevice> gpu = nullptr;
};

// The device a Renderer whose settings name none renders on (null: the CPU). `tandem experiment
// --device` sets it for the renders of an experiment, whose runners make their own settings.
std::shared_ptr<GpuDevice> defaultRenderDevice();
// Makes `device` the default until destroyed (the previous one back then).
class ScopedRenderDevice {
 public:
  explicit ScopedRenderDevice(std::shared_ptr<GpuDevice> device);
  ~ScopedRenderDevice();
  ScopedRenderDevice(const ScopedRenderDevice&) = delete;
  ScopedRenderDevice& operator=(const ScopedRenderDevice&) = delete;

 private:
  std::shared_ptr<GpuDevice> previous_;
};

class Renderer {
 public:
  Renderer(const Scene& scene, Pipeline pipeline, RenderSettings settings);

  // Renders frame `index` seen through `camera` (scene time index / frameRate), with an optional
  // sub-pixel jitter in pixels (overrides a pass's jitter request when non-zero); motion vectors
  // never include the jitter.
  FrameTimings renderFrame(int index, const CameraDesc& camera, Vec2 jitter = {0, 0});
  // Renders at scene time `time` (seconds); `shutterClose` is the camera when the shutter closes
  // (motion blur over settings.shutter seconds; the same camera for a still one).
  FrameTimings renderFrameAt(int index, float time, const CameraDesc& camera,
                             const CameraDesc& shutterClose, Vec2 jitter = {0, 0});
  // The output's / buffer `name`'s current value on the host: downloaded first where only the
  // device holds it (a renderer that keeps buffers there, keepOnDevice).
  const Buffer& output() { return fetch(pipeline_.output); }
  const Buffer& fetch(const std::string& name);
  // On a GPU, buffers stay where they were written at a frame's end, read back only through
  // output() and fetch(): a timed frame pays no readback the CPU's frame does not (experiments).
  void keepOnDevice() {
    ctx_.outputToHost = false;
    ctx_.allToHost = false;
  }
  FrameContext& context() { return ctx_; }
  const FrameContext& context() const { return ctx_; }
  Pipeline& pipeline() { return pipeline_; }
  const RenderSettings& settings() const { return settings_; }

  // History resets: each starts every temporal pass over on the next frame.
  void cut() { resetHistory("camera cut"); }  // the next camera is unrelated
  void resize(int width, int height);         // a new frame size
  void setScene(const Scene& scene);          // a (re)loaded scene
  void setPipeline(Pipeline pipeline);        // a pipeline switch
  void resetHistory(const std::string& reason);
  const std::string& lastResetReason() const { return resetReason_; }
  int resets() const { return resets_; }  // how many resets fired (tests)

 private:
  void applySize();
  void makeViews(const CameraDesc& camera, const CameraDesc& shutterClose, Vec2 jitter);

  const Scene* scene_;
  Pipeline pipeline_;
  RenderSettings settings_;
  FrameContext ctx_;
  bool first_ = true;
  CameraDesc lastCamera_;
  float lastTime_ = 0;
  int jitterIndex_ = 0;
  std::string resetReason_;
  int resets_ = 0;
};

}  // namespace tandem
