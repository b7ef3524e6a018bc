// What the heuristic and rt_secondary hand each other, as typed records (BufferKind::Record):
// this frame's request (`rt_request`: whether to time each object and effect, and a deadline),
// and what rt_secondary measured (`rt_stats`), which the heuristic reads the next frame as a
// history input to price its nodes (Walewski et al. 2019's frame-to-frame feedback).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/buffer.h"
#include "passes/heuristic/effect_channels.h"

namespace tandem {

struct RtRequest {
  bool timeEffects = false;  // time each object and effect (the ms budget prices with it)
  double deadlineMs = 0;     // > 0: stop tracing at this many ms (the deadline mode)
};

struct RtStats {
  bool timeEffects = false;  // cpuMs was measured (the heuristic asked for it)
  double ms = 0;             // wall time of the pass; 0: the pass did not run
  std::vector<std::array<uint64_t, kEffectCount>> pixels, rays;  // per object, per effect
  std::vector<std::array<double, kEffectCount>> cpuMs;  // thread time per object and effect
};

inline BufferSlot rtRequestSlot(bool asInput) {
  BufferSlot s = recordSlot("rt_request", "RtRequest");
  s.optional = asInput;
  return s;
}
inline BufferSlot rtStatsSlot(bool asHistoryInput) {
  BufferSlot s = recordSlot("rt_stats", "RtStats");
  s.history = s.optional = asHistoryInput;
  return s;
}

}  // namespace tandem
