#include "pipeline/renderer.h"

#include <cstring>
#include <mutex>
#include <utility>

#include "pipeline/gpu_frame.h"

namespace tandem {

namespace {
std::mutex defaultDeviceMutex;
std::shared_ptr<GpuDevice> defaultDevice;
}  // namespace

std::shared_ptr<GpuDevice> defaultRenderDevice() {
  const std::lock_guard<std::mutex> lock(defaultDeviceMutex);
  return defaultDevice;
}

ScopedRenderDevice::ScopedRenderDevice(std::shared_ptr<GpuDevice> device) {
  const std::lock_guard<std::mutex> lock(defaultDeviceMutex);
  previous_ = std::exchange(defaultDevice, std::move(device));
}

ScopedRenderDevice::~ScopedRenderDevice() {
  const std::lock_guard<std::mutex> lock(defaultDeviceMutex);
  defaultDevice = std::move(previous_);
}

Renderer::Renderer(const Scene& scene, Pipeline pipeline, RenderSettings settings)
    : scene_(&scene), pipeline_(std::move(pipeline)), settings_(settings) {
  ctx_.scene = scene_;
  ctx_.seed = settings.seed;
  ctx_.textureFootprint = settings.textureFootprint;
  if (!settings_.gpu) settings_.gpu = defaultRenderDevice();
  if (settings_.gpu) ctx_.gpu = std::make_shared<GpuFrame>(settings_.gpu);
  applySize();
  resetHistory("first frame");
}

const Buffer& Renderer::fetch(const std::string& name) {
  if (ctx_.gpu && ctx_.gpu->deviceNewer(name)) {
    auto it = ctx_.buffers.find(name);
    if (it != ctx_.buffers.end()) ctx_.gpu->download(name, it->second);
  }
  return ctx_.input(name);
}

void Renderer::resetHistory(const std::string& reason) {
  ctx_.historyReset = true;
  resetReason_ = reason;
  ++resets_;
}

void Renderer::applySize() {
  ctx_.width = settings_.width * (settings_.stereo.enabled ? 2 : 1);
  ctx_.height = settings_.height;
}

void Renderer::resize(int width, int height) {
  settings_.width = width;
  settings_.height = height;
  applySize();
  resetHistory("resize");
}

void Renderer::setScene(const Scene& scene) {
  scene_ = &scene;
  ctx_.scene = scene_;
  ctx_.frame = FrameScene{};
  if (ctx_.gpu) ctx_.gpu->sceneChanged();  // the same Scene may come back with other lights
  first_ = true;
  resetHistory("scene reload");
}

void Renderer::setPipeline(Pipeline pipeline) {
  pipeline_ = std::move(pipeline);
  ctx_.buffers.clear();  // another pipeline's buffers must not look produced
  if (ctx_.gpu) ctx_.gpu->forget();
  resetHistory("pipeline switch");
}

FrameTimings Renderer::renderFrame(int index, const CameraDesc& camera, Vec2 jitter) {
  return renderFrameAt(index, float(index) / settings_.frameRate, camera, camera, jitter);
}

void Renderer::makeViews(const CameraDesc& camera, const CameraDesc& shutterClose, Vec2 jitter) {
  const CameraDesc prevDesc = first_ ? camera : lastCamera_;
  const int eyes = settings_.stereo.enabled ? 2 : 1;
  const int w = settings_.width, h = settings_.height;
  ctx_.views.resize(size_t(eyes));
  for (int e = 0; e < eyes; ++e) {
    View& v = ctx_.views[size_t(e)];
    const StereoDesc& st = settings_.stereo;
    v.camera = Camera::make(eyeCamera(camera, st, e), w, h);
    v.jitter = jitter;
    v.jitteredCamera = Camera::make(v.camera.desc, w, h, jitter);
    v.prevCamera = Camera::make(eyeCamera(prevDesc, st, e), w, h);
    v.shutterCamera = Camera::make(eyeCamera(shutterClose, st, e), w, h);
    v.x = e * w;
    v.y = 0;
    v.cameraMoved = std::memcmp(&v.camera.viewProjUnjittered, &v.prevCamera.viewProjUnjittered,
                                sizeof(Mat4)) != 0;
  }
}

FrameTimings Renderer::renderFrameAt(int index, float t, const CameraDesc& camera,
                                     const CameraDesc& shutterClose, Vec2 jitter) {
  // The first frame has no history: it is its own previous frame (zero motion, unless animated
  // objects moved during the frame interval, which we take from t - 1/frameRate).
  float tPrev = first_ ? t - 1.0f / settings_.frameRate : lastTime_;
  // A change of lens or field of view is a new picture for every temporal pass.
  if (!first_ &&
      (camera.vfovDeg != lastCamera_.vfovDeg || camera.projection != lastCamera_.projection ||
       camera.apertureDiameter != lastCamera_.apertureDiameter ||
       camera.focusDistance != lastCamera_.focusDistance ||
       camera.apertureBlades != lastCamera_.apertureBlades))
    resetHistory("lens change");
  auto t0 = Clock::now();
  ctx_.frame.update(*scene_, t, tPrev, settings_.shutter);
  double updateMs = msSince(t0);
  ctx_.frameIndex = index;
  const FrameRequest req = pipeline_.request();
  if (jitter.x == 0 && jitter.y == 0 && req.jitter)
    jitter = haltonJitter(1 + jitterIndex_++ % std::max(req.jitterPhases, 1));
  ctx_.jitter = jitter;
  makeViews(camera, shutterClose, jitter);
  FrameTimings ft = pipeline_.execute(ctx_);
  ft.passes.insert(ft.passes.begin(), PassTiming{"scene_update", updateMs, 0});
  ft.totalMs += updateMs;
  first_ = false;
  lastCamera_ = camera;
  lastTime_ = t;
  return ft;
}

}  // namespace tandem
