// What rt_secondary measured, as a declared buffer (`rt_stats`, a list): the heuristic reads last
// frame's value as a history input to price its nodes (seed 002's frame-to-frame feedback).
// Layout: one record per object (pixels, rays, CPU ms per effect: 9 channels), then one record
// with the pass's wall time in ms and whether effects were timed.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/buffer.h"
#include "passes/heuristic/effect_channels.h"

namespace tandem {

struct RtStats {
  bool timeEffects = false;  // cpuMs was measured (the heuristic asked for it)
  double ms = 0;             // wall time of the pass; 0: the pass did not run
  std::vector<std::array<uint64_t, kEffectCount>> pixels, rays;  // per object, per effect
  std::vector<std::array<double, kEffectCount>> cpuMs;  // thread time per object and effect
};

constexpr int kRtStatsChannels = 3 * kEffectCount;
BufferSlot rtStatsSlot(bool asHistoryInput);
void writeRtStats(const RtStats& stats, Buffer& out);  // out sized objects + 1 by 1
RtStats readRtStats(const Buffer& b);

}  // namespace tandem
