// Per-pass timings over the last N frames, for the viewer's profiler: the current value, the
// average over the window, frames per second and rays per second of passes that count rays.
#pragma once
#include <deque>
#include <string>
#include <vector>

#include "core/profiler.h"

namespace tandem {

class FrameHistory {
 public:
  explicit FrameHistory(size_t window = 60) : window_(window) {}
  void add(const FrameTimings& t);
  void clear() { frames_.clear(); }
  size_t size() const { return frames_.size(); }
  const std::deque<FrameTimings>& frames() const { return frames_; }

  struct PassRow {
    std::string name;
    double currentMs = 0, averageMs = 0, raysPerSecond = 0;  // rays/s over the window (0: none)
  };
  // Passes of the newest frame, in order (sub-timings "pass/part" included).
  std::vector<PassRow> rows() const;
  double averageFrameMs() const;
  double framesPerSecond() const;  // from the average frame time

 private:
  size_t window_;
  std::deque<FrameTimings> frames_;
};

}  // namespace tandem
