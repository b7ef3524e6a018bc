// A cheap clock for timing many short events (one per pixel and effect): the CPU's time-stamp
// counter where there is one (constant-rate and synchronised across cores on current x86),
// steady_clock nanoseconds elsewhere. Ticks become milliseconds through a rate measured against
// steady_clock over a longer interval (TickRate).
#pragma once
#include <chrono>
#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

namespace tandem {

inline uint64_t cycleNow() {
#if defined(__x86_64__) || defined(__i386__)
  return __rdtsc();
#else
  return uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(
                      std::chrono::steady_clock::now().time_since_epoch())
                      .count());
#endif
}

// Ticks per millisecond over [start, stop()] (call stop() after at least ~1 ms of work).
class TickRate {
 public:
  TickRate() : t0_(std::chrono::steady_clock::now()), c0_(cycleNow()) {}
  double ticksPerMs() const {
    double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0_).count();
    uint64_t c = cycleNow();
    return ms > 0 && c > c0_ ? double(c - c0_) / ms : 1e6;
  }

 private:
  std::chrono::steady_clock::time_point t0_;
  uint64_t c0_;
};

}  // namespace tandem
