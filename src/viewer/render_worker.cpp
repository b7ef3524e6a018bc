#include "viewer/render_worker.h"

#include <chrono>
#include <memory>

#include "core/error.h"
#include "pipeline/aov.h"
#include "pipeline/renderer.h"

namespace tandem {

PipelineModel PipelineModel::from(const Pipeline& p, const std::string& source) {
  PipelineModel m;
  m.source = source;
  for (const auto& pass : p.passes) {
    PassModel pm;
    pm.label = pass->label.empty() ? pass->type() : pass->label;
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

RenderWorker::RenderWorker(const Scene& scene, PipelineModel model, ViewState view, uint64_t seed)
    : scene_(scene), seed_(seed), view_(std::move(view)), model_(std::move(model)) {
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
  if (latest_.serial == 0 || latest_.serial == taken_) return false;
  out = latest_;
  taken_ = latest_.serial;
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

void RenderWorker::loop() {
  std::unique_ptr<Renderer> renderer;
  int frameIndex = 0;
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
    FinishedFrame f;
    try {
      // Only the shown buffer and what the passes read are produced.
      FrameContext& c = renderer->context();
      c.keepAllOutputs = false;
      c.wanted.clear();
      if (!view.shownBuffer.empty()) c.wanted.insert(view.shownBuffer);
      f.timings = renderer->renderFrameAt(frameIndex, view.time, view.camera, view.camera);
      ++frameIndex;
      FrameContext& ctx = renderer->context();
      f.samplesPerPixel = ctx.counters.count("spp") ? int(ctx.counters.at("spp")) : 0;
      f.buffers = renderer->pipeline().producedBuffers();
      const std::string& outName = renderer->pipeline().output;
      f.shown = view.shownBuffer.empty() || !ctx.buffers.count(view.shownBuffer) ? outName
                                                                                 : view.shownBuffer;
      f.output = ctx.input(outName);
      // Shown at its own size (a reduced-extent buffer is stretched over the window).
      const Buffer shown = visualizeBuffer(ctx.input(f.shown), view.varianceScale);
      f.width = shown.width;
      f.height = shown.height;
      f.rgba.resize(shown.pixelCount() * 4);
      for (size_t i = 0; i < shown.pixelCount(); ++i) {
        for (int c = 0; c < 3; ++c)
          f.rgba[i * 4 + size_t(c)] =
              uint8_t(std::lround(std::clamp(shown.data[i * 3 + size_t(c)], 0.0f, 1.0f) * 255.0f));
        f.rgba[i * 4 + 3] = 255;
      }
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = e.what();
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      f.serial = ++finished_;
      latest_ = std::move(f);
    }
    done_.notify_all();
  }
  done_.notify_all();
}

}  // namespace tandem
