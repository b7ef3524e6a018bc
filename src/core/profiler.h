// Per-pass timings, always on: a pipeline records milliseconds and counters for every pass
// every frame; bench and the viewer summarise them.
#pragma once
#include <chrono>
#include <map>
#include <string>
#include <vector>

namespace tandem {

using Clock = std::chrono::steady_clock;

inline double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct PassTiming {
  std::string name;
  double ms = 0;
  double rays = 0;   // rays traced by the pass this frame (0 when it traces none)
  double bytes = 0;  // bytes a move between host and GPU carried (its own row)
};

struct FrameTimings {
  std::vector<PassTiming> passes;
  double totalMs = 0;
};

struct TimingStats {
  double median = 0, mean = 0, min = 0, max = 0;
};
TimingStats summarize(std::vector<double> samples);

}  // namespace tandem
