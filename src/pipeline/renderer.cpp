#include "pipeline/renderer.h"

#include <cstring>

namespace tandem {

Renderer::Renderer(const Scene& scene, Pipeline pipeline, RenderSettings settings)
    : scene_(scene), pipeline_(std::move(pipeline)), settings_(settings) {
  ctx_.scene = &scene_;
  ctx_.width = settings.width;
  ctx_.height = settings.height;
  ctx_.seed = settings.seed;
}

FrameTimings Renderer::renderFrame(int index, const CameraDesc& camera, Vec2 jitter) {
  return renderFrameAt(index, float(index) / settings_.frameRate, camera, camera, jitter);
}

FrameTimings Renderer::renderFrameAt(int index, float t, const CameraDesc& camera,
                                     const CameraDesc& shutterClose, Vec2 jitter) {
  // The first frame has no history: it is its own previous frame (zero motion, unless animated
  // objects moved during the frame interval, which we take from t - 1/frameRate).
  float tPrev = first_ ? t - 1.0f / settings_.frameRate : lastTime_;
  CameraDesc prevDesc = first_ ? camera : lastCamera_;
  auto t0 = Clock::now();
  ctx_.frame.update(scene_, t, tPrev, settings_.shutter);
  double updateMs = msSince(t0);
  ctx_.frameIndex = index;
  ctx_.camera = Camera::make(camera, settings_.width, settings_.height, jitter);
  ctx_.prevCamera = Camera::make(prevDesc, settings_.width, settings_.height);
  ctx_.shutterCamera = Camera::make(shutterClose, settings_.width, settings_.height, jitter);
  ctx_.cameraMoved = std::memcmp(&ctx_.camera.viewProjUnjittered,
                                 &ctx_.prevCamera.viewProjUnjittered, sizeof(Mat4)) != 0;
  FrameTimings ft = pipeline_.execute(ctx_);
  ft.passes.insert(ft.passes.begin(), PassTiming{"scene_update", updateMs, 0});
  ft.totalMs += updateMs;
  first_ = false;
  lastCamera_ = camera;
  lastTime_ = t;
  return ft;
}

}  // namespace tandem
