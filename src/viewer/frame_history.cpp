#include "viewer/frame_history.h"

namespace tandem {

void FrameHistory::add(const FrameTimings& t) {
  frames_.push_back(t);
  while (frames_.size() > window_) frames_.pop_front();
}

std::vector<FrameHistory::PassRow> FrameHistory::rows() const {
  std::vector<PassRow> out;
  if (frames_.empty()) return out;
  for (const PassTiming& p : frames_.back().passes) {
    PassRow r;
    r.name = p.name;
    r.currentMs = p.ms;
    double ms = 0, rays = 0;
    size_t n = 0;
    for (const FrameTimings& f : frames_)
      for (const PassTiming& q : f.passes)
        if (q.name == p.name) ms += q.ms, rays += q.rays, ++n;
    r.averageMs = n ? ms / double(n) : 0.0;
    r.raysPerSecond = ms > 0 ? rays / (ms * 1e-3) : 0.0;
    out.push_back(r);
  }
  return out;
}

double FrameHistory::averageFrameMs() const {
  double s = 0;
  for (const FrameTimings& f : frames_) s += f.totalMs;
  return frames_.empty() ? 0.0 : s / double(frames_.size());
}

double FrameHistory::framesPerSecond() const {
  const double ms = averageFrameMs();
  return ms > 0 ? 1000.0 / ms : 0.0;
}

}  // namespace tandem
