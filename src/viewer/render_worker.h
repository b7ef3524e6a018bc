// The viewer's renderer runs on its own thread: the window thread posts the view (camera, size,
// buffer to show) and pipeline edits, and takes the last finished frame whenever it draws, so
// the interface stays responsive however long a frame takes. No UI library here, so the worker
// is tested without a display.
#pragma once
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "gpu/gpu_device.h"
#include "pipeline/pipeline.h"
#include "scene/scene.h"

namespace tandem {

// What the panel edits: a pipeline by source plus every pass's switch and parameter values.
struct PipelineModel {
  struct PassModel {
    std::string label, type;
    bool enabled = true;
    std::map<std::string, double> values;
  };
  std::string source;  // built-in name or JSON file
  std::vector<PassModel> passes;

  static PipelineModel from(const Pipeline& p, const std::string& source);
  static PipelineModel load(const std::string& source);  // throws InputError
  Pipeline build() const;                                // source + switches + values
};

struct ViewState {
  CameraDesc camera;
  int width = 640, height = 360;  // one eye in stereo
  StereoDesc stereo;              // both eyes side by side (the frame is 2 x width wide)
  float time = 0;                 // scene time (seconds)
  std::string shownBuffer;        // empty: the pipeline's output
  float varianceScale = 10;       // for the variance view
};

struct FinishedFrame {
  std::vector<uint8_t> rgba;  // display-encoded, top row first
  int width = 0, height = 0;
  FrameTimings timings;
  int samplesPerPixel = 0;           // progressive passes (0: none)
  uint64_t serial = 0;               // frames rendered so far, this one included
  std::vector<std::string> buffers;  // what can be shown
  std::string shown;
  Buffer output;  // the pipeline's output buffer as rendered (for screenshots)
};

class RenderWorker {
 public:
  // `gpu`: the device passes with a GPU version run on (null: the CPU).
  RenderWorker(const Scene& scene, PipelineModel model, ViewState view, uint64_t seed = 0,
               std::shared_ptr<GpuDevice> gpu = nullptr);
  ~RenderWorker();
  RenderWorker(const RenderWorker&) = delete;
  RenderWorker& operator=(const RenderWorker&) = delete;

  void setView(const ViewState& v);
  void setPipeline(const PipelineModel& m);  // switch pipelines (rebuilt between frames)
  void setParam(size_t pass, const std::string& name, double value);
  void setEnabled(size_t pass, bool enabled);

  // Copies the newest finished frame if it is newer than the last one taken.
  bool takeFrame(FinishedFrame& out);
  // Blocks until `n` frames have finished since start (tests, scripted screenshots).
  void waitForFrames(uint64_t n);
  uint64_t framesFinished() const;
  // The last error an edit or a frame raised (e.g. a value out of range); cleared by the next
  // edit or pipeline switch that succeeds.
  std::string error() const;

 private:
  void loop();

  const Scene& scene_;
  uint64_t seed_;
  std::shared_ptr<GpuDevice> gpu_;
  mutable std::mutex mutex_;
  std::condition_variable done_;
  ViewState view_;
  PipelineModel model_;
  bool rebuild_ = true;
  std::vector<std::pair<size_t, std::pair<std::string, double>>> paramEdits_;
  std::vector<std::pair<size_t, bool>> enableEdits_;
  FinishedFrame latest_;
  uint64_t taken_ = 0, finished_ = 0;
  std::string error_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace tandem
