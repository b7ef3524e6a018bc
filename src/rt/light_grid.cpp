#include "rt/light_grid.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "rt/sampler.h"

namespace tandem {

namespace {

// The light's unshadowed irradiance at normal incidence in the cell [lo, hi], as estimated for
// selection (see the header); the colour's sum stands for its strength.
float cellEstimate(const PreparedLight& l, Vec3 lo, Vec3 hi) {
  const float strength = std::max(l.power.x + l.power.y + l.power.z, 0.0f);
  if (l.type == LightType::Directional) return strength;
  const Vec3 closest = vmin(vmax(l.position, lo), hi);
  const Vec3 toClosest = l.position - closest;
  if (l.range > 0.0f && dot(toClosest, toClosest) > l.range * l.range) return 0.0f;
  const Vec3 c = (lo + hi) * 0.5f, half = (hi - lo) * 0.5f;
  const Vec3 toCentre = l.position - c;
  const float d = std::max(std::sqrt(dot(toCentre, toCentre)), std::sqrt(dot(half, half)));
  const float att =
      1.0f / std::max(l.attConstant + l.attLinear * d + l.attQuadratic * d * d, 1e-8f);
  return strength * att;
}

}  // namespace

LightGrid::LightGrid(const std::vector<PreparedLight>& lights, std::vector<int> candidates,
                     Bounds3 bounds, const Visibility& visible, int cellsPerAxis, size_t maxEntries,
                     int probes, size_t maxProbes)
    : candidates_(std::move(candidates)) {
  const size_t n = candidates_.size();
  if (n <= 1) return;  // nothing to choose
  if (bounds.empty()) bounds.lo = bounds.hi = Vec3(0.0f);
  const Vec3 e = bounds.extent();
  const float longest = std::max({e.x, e.y, e.z, 1e-6f});
  float cell = longest / float(std::max(cellsPerAxis, 1));
  for (;;) {
    size_t total = n;
    for (int a = 0; a < 3; ++a) {
      const float ext = a == 0 ? e.x : a == 1 ? e.y : e.z;
      dims_[a] = std::max(1, int(std::ceil(ext / cell)));
      total *= size_t(dims_[a]);
    }
    if (total <= maxEntries || (dims_[0] == 1 && dims_[1] == 1 && dims_[2] == 1)) break;
    cell *= 1.25f;
  }
  // Cells of equal size starting at bounds.lo (the last may reach past bounds.hi).
  bounds_.lo = bounds.lo;
  bounds_.hi = bounds.lo + Vec3(float(dims_[0]), float(dims_[1]), float(dims_[2])) * cell;
  invCell_ = Vec3(1.0f / cell);
  const size_t cellCount = size_t(dims_[0]) * size_t(dims_[1]) * size_t(dims_[2]);
  cdf_.assign(cellCount * n, 0.0f);
  // Probes per cell and light within the budget (none below 2: too coarse to be worth it).
  if (visible) probes = std::min<size_t>(size_t(std::max(probes, 0)), maxProbes / (cellCount * n));
  if (!visible || probes < 2) probes = 0;
  std::atomic<size_t> traced{0};
  tbb::parallel_for(size_t(0), cellCount, [&](size_t k) {
    const int ix = int(k % size_t(dims_[0]));
    const int iy = int(k / size_t(dims_[0]) % size_t(dims_[1]));
    const int iz = int(k / (size_t(dims_[0]) * size_t(dims_[1])));
    const Vec3 lo = bounds_.lo + Vec3(float(ix), float(iy), float(iz)) * cell;
    const Vec3 hi = lo + Vec3(cell);
    float* c = &cdf_[k * n];
    double sum = 0;
    size_t last = n;
    size_t localTraced = 0;
    for (size_t i = 0; i < n; ++i) {
      float w = cellEstimate(lights[size_t(candidates_[i])], lo, hi);
      if (w > 0.0f && probes > 0) {
        int seen = 0;
        for (int j = 0; j < probes; ++j) {
          // A point of the cell from a hash of (cell, light, probe): the same grid every build.
          const uint32_t h = hashCombine(hashCombine(uint32_t(k), uint32_t(i)), uint32_t(j));
          const Vec3 r(float(hashCombine(h, 1u) >> 8) * 0x1p-24f,
                       float(hashCombine(h, 2u) >> 8) * 0x1p-24f,
                       float(hashCombine(h, 3u) >> 8) * 0x1p-24f);
          // Inside the bounds only: the last cells reach past them, beyond the outer walls.
          const Vec3 plo = vmax(lo, bounds.lo), phi = vmax(vmin(hi, bounds.hi), plo);
          seen += visible(plo + (phi - plo) * r, candidates_[i]) ? 1 : 0;
        }
        localTraced += size_t(probes);
        w *= (float(seen) + 0.5f) / float(probes + 1);
      }
      if (w > 0.0f) last = i;
      sum += double(w);
      c[i] = float(sum);
    }
    traced += localTraced;
    if (last == n) {  // no candidate reaches the cell: leave it all zero (uniform)
      std::fill(c, c + n, 0.0f);
      return;
    }
    for (size_t i = 0; i < n; ++i) c[i] = i >= last ? 1.0f : float(double(c[i]) / sum);
  });
  probeRays_ = traced.load();
}

size_t LightGrid::cellOf(Vec3 p) const {
  const Vec3 f = (p - bounds_.lo) * invCell_;
  const auto clampAxis = [&](float v, int a) {
    return size_t(std::clamp(int(std::floor(std::clamp(v, -1.0f, 1e6f))), 0, dims_[a] - 1));
  };
  return clampAxis(f.x, 0) +
         size_t(dims_[0]) * (clampAxis(f.y, 1) + size_t(dims_[1]) * clampAxis(f.z, 2));
}

LightGrid::Pick LightGrid::pick(Vec3 p, float u) const {
  const size_t n = candidates_.size();
  if (n == 0) return {};
  if (n == 1) return {candidates_[0], 1.0f};
  u = std::clamp(u, 0.0f, 0x1.fffffep-1f);
  const float* c = &cdf_[cellOf(p) * n];
  if (c[n - 1] <= 0.0f) {
    const size_t i = std::min(size_t(u * float(n)), n - 1);
    return {candidates_[i], 1.0f / float(n)};
  }
  const size_t i = std::min(size_t(std::upper_bound(c, c + n, u) - c), n - 1);
  return {candidates_[i], c[i] - (i ? c[i - 1] : 0.0f)};
}

float LightGrid::probability(Vec3 p, int light) const {
  const size_t n = candidates_.size();
  const auto it = std::find(candidates_.begin(), candidates_.end(), light);
  if (it == candidates_.end()) return 0.0f;
  if (n == 1) return 1.0f;
  const size_t i = size_t(it - candidates_.begin());
  const float* c = &cdf_[cellOf(p) * n];
  if (c[n - 1] <= 0.0f) return 1.0f / float(n);
  return c[i] - (i ? c[i - 1] : 0.0f);
}

uint64_t lightSetKey(const std::vector<PreparedLight>& lights, const std::vector<int>& candidates) {
  // FNV-1a over the fields the estimate reads.
  uint64_t h = 1469598103934665603ull;
  const auto mix = [&](const void* data, size_t bytes) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) h = (h ^ b[i]) * 1099511628211ull;
  };
  for (int i : candidates) {
    const PreparedLight& l = lights[size_t(i)];
    const float f[9] = {l.power.x,    l.power.y,     l.power.z,   l.position.x,  l.position.y,
                        l.position.z, l.attConstant, l.attLinear, l.attQuadratic};
    mix(&i, sizeof i);
    mix(&l.type, sizeof l.type);
    mix(f, sizeof f);
    mix(&l.range, sizeof l.range);
  }
  return h;
}

}  // namespace tandem
