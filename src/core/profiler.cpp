#include "core/profiler.h"

#include <algorithm>
#include <numeric>

namespace tandem {

TimingStats summarize(std::vector<double> v) {
  TimingStats s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  s.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  s.mean = std::accumulate(v.begin(), v.end(), 0.0) / double(n);
  s.min = v.front();
  s.max = v.back();
  return s;
}

}  // namespace tandem
