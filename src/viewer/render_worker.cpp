#include "viewer/render_worker.h"

#include <algorithm>
#include <chrono>
#include <memory>

#include "core/error.h"
#include "core/parallel.h"
#include "passes/baselines/pt_reference.h"
#include "pipeline/aov.h"
#include "pipeline/renderer.h"

namespace tandem {

PipelineModel PipelineModel::from(const Pipeline& p, const std::string& source) {
  PipelineModel m;
  m.source = source;
  for (const auto& pass : p.passes) {
    PassModel pm;
    pm.label = pass->name();
    pm.type = pass->type();
    pm.enabled = pass->enabled;
    for (const ParamDesc& d : pass->params()) pm.values[d.name] = pass->param(d.name);
    m.passes.push_back(pm);
  }
  return m;
}

PipelineModel PipelineModel::load(const std::string& source) {
  return from(Pipeline::load(source), source);
}

Pipeline PipelineModel::build() const {
  Pipeline p = Pipeline::load(source);
  for (size_t i = 0; i < p.passes.size() && i < passes.size(); ++i) {
    p.passes[i]->enabled = passes[i].enabled;
    for (const auto& [name, v] : passes[i].values) p.passes[i]->setParam(name, v);
  }
  return p;
}

RenderWorker::RenderWorker(const Scene& scene, PipelineModel model, ViewState view, uint64_t seed,
                           std::shared_ptr<GpuDevice> gpu)
    : scene_(scene),
      seed_(seed),
      gpu_(std::move(gpu)),
      view_(std::move(view)),
      model_(std::move(model)) {
  thread_ = std::thread([this] { loop(); });
}

RenderWorker::~RenderWorker() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void RenderWorker::setView(const ViewState& v) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (v.width != view_.width || v.height != view_.height ||
      v.stereo.enabled != view_.stereo.enabled || v.stereo.ipd != view_.stereo.ipd ||
      v.stereo.converged != view_.stereo.converged ||
      v.stereo.convergence != view_.stereo.convergence)
    rebuild_ = true;
  view_ = v;
}

void RenderWorker::setPipeline(const PipelineModel& m) {
  std::lock_guard<std::mutex> lock(mutex_);
  model_ = m;
  paramEdits_.clear();
  enableEdits_.clear();
  rebuild_ = true;
}

void RenderWorker::setParam(size_t pass, const std::string& name, double value) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (pass < model_.passes.size()) model_.passes[pass].values[name] = value;
  paramEdits_.push_back({pass, {name, value}});
}

void RenderWorker::setEnabled(size_t pass, bool enabled) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (pass < model_.passes.size()) model_.passes[pass].enabled = enabled;
  enableEdits_.push_back({pass, enabled});
}

bool RenderWorker::takeFrame(FinishedFrame& out) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (latest_.serial <= taken_) return false;
  // Swapped, not copied: the caller's last frame goes back to the worker, which refills it
  // (no 8 MB copy under the lock, no fresh pages each frame).
  std::swap(out, latest_);
  taken_ = out.serial;
  return true;
}

void RenderWorker::waitForFrames(uint64_t n) {
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [&] { return finished_ >= n || stop_; });
}

uint64_t RenderWorker::framesFinished() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return finished_;
}

std::string RenderWorker::error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

namespace {
// Display-encoded RGB (3+ channels: a pipeline's output, or a visualized buffer) -> RGBA8, top row
// first, rows in parallel. Rounds as std::lround does for values in [0, 255] (floor(x + 0.5), the
// addition's rounding undone), in a loop the compiler vectorises.
void toRgba8(const Buffer& rgb, std::vector<uint8_t>& rgba) {
  rgba.resize(rgb.pixelCount() * 4);
  const int w = rgb.width, c = rgb.channels;
  parallelRows(rgb.height, [&](int y) {
    const float* in = rgb.at(0, y);
    uint8_t* out = &rgba[size_t(y) * size_t(w) * 4];
    for (int x = 0; x < w; ++x) {
      for (int k = 0; k < 3; ++k) {
        const float v = std::clamp(in[x * c + k], 0.0f, 1.0f) * 255.0f;
        int r = int(v + 0.5f);
        if (float(r) - 0.5f > v) --r;
        out[4 * x + k] = uint8_t(r);
      }
      out[4 * x + 3] = 255;
    }
  });
}
}  // namespace

void RenderWorker::loop() {
  std::unique_ptr<Renderer> renderer;
  int frameIndex = 0;
  FinishedFrame f;  // refilled every frame (its storage cycles with latest_ and the taker's)
  while (!stop_) {
    ViewState view;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      view = view_;
      try {
        const bool edits = rebuild_ || !paramEdits_.empty() || !enableEdits_.empty();
        if (rebuild_ || !renderer) {
          RenderSettings rs{
              .width = std::max(view.width, 1), .height = std::max(view.height, 1), .seed = seed_};
          rs.stereo = view.stereo;
          rs.gpu = gpu_;
          renderer = std::make_unique<Renderer>(scene_, model_.build(), rs);
          rebuild_ = false;
        } else {
          Pipeline& p = renderer->pipeline();
          for (auto& [i, e] : paramEdits_)
            if (i < p.passes.size()) p.passes[i]->setParam(e.first, e.second);
          for (auto& [i, on] : enableEdits_)
            if (i < p.passes.size()) p.passes[i]->enabled = on;
        }
        if (edits) error_.clear();
      } catch (const std::exception& e) {
        error_ = e.what();
      }
      paramEdits_.clear();
      enableEdits_.clear();
    }
    if (!renderer) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    try {
      // Only the shown buffer and what the passes read are produced.
      FrameContext& c = renderer->context();
      c.keepAllOutputs = false;
      c.wanted.clear();
      if (!view.shownBuffer.empty()) c.wanted.insert(view.shownBuffer);
      f.timings = renderer->renderFrameAt(frameIndex, view.time, view.camera, view.camera);
      ++frameIndex;
      FrameContext& ctx = renderer->context();
      f.samplesPerPixel = int(ctx.counter(PTReferenceCounters::spp, 0));
      f.buffers = renderer->pipeline().producedBuffers();
      const std::string& outName = renderer->pipeline().output;
      f.shown = view.shownBuffer.empty() || !ctx.buffers.count(view.shownBuffer) ? outName
                                                                                 : view.shownBuffer;
      f.output = ctx.input(outName);
      // Shown at its own size (a reduced-extent buffer is stretched over the window).
      const Buffer& shown = ctx.input(f.shown);
      if (shown.kind == BufferKind::Display && shown.channels >= 3)
        toRgba8(shown, f.rgba);
      else
        toRgba8(visualizeBuffer(shown, view.varianceScale), f.rgba);
      f.width = shown.width;
      f.height = shown.height;
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = e.what();
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      f.serial = ++finished_;
      std::swap(latest_, f);
    }
    done_.notify_all();
  }
  done_.notify_all();
}

}  // namespace tandem
