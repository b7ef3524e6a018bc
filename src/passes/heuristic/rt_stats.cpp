#include "passes/heuristic/rt_stats.h"

namespace tandem {

BufferSlot rtStatsSlot(bool asHistoryInput) {
  BufferSlot s{"rt_stats", kRtStatsChannels, BufferKind::List, Extent::any()};
  s.history = s.optional = asHistoryInput;
  return s;
}

void writeRtStats(const RtStats& stats, Buffer& out) {
  const size_t n = stats.pixels.size();
  out.fill(0.0f);
  for (size_t o = 0; o < n; ++o) {
    float* r = out.at(int(o), 0);
    for (size_t e = 0; e < size_t(kEffectCount); ++e) {
      r[e] = float(stats.pixels[o][e]);
      r[kEffectCount + e] = float(stats.rays[o][e]);
      r[2 * kEffectCount + e] = o < stats.cpuMs.size() ? float(stats.cpuMs[o][e]) : 0.0f;
    }
  }
  float* h = out.at(int(n), 0);
  h[0] = float(stats.ms);
  h[1] = stats.timeEffects ? 1.0f : 0.0f;
}

RtStats readRtStats(const Buffer& b) {
  RtStats s;
  if (b.width < 1 || b.channels != kRtStatsChannels) return s;
  const size_t n = size_t(b.width) - 1;
  s.pixels.resize(n);
  s.rays.resize(n);
  s.cpuMs.resize(n);
  for (size_t o = 0; o < n; ++o) {
    const float* r = b.at(int(o), 0);
    for (size_t e = 0; e < size_t(kEffectCount); ++e) {
      s.pixels[o][e] = uint64_t(r[e]);
      s.rays[o][e] = uint64_t(r[kEffectCount + e]);
      s.cpuMs[o][e] = r[2 * kEffectCount + e];
    }
  }
  s.ms = b.at(int(n), 0)[0];
  s.timeEffects = b.at(int(n), 0)[1] != 0;
  return s;
}

}  // namespace tandem
