#include "shading/light_cull_grid.h"

#include <algorithm>
#include <cmath>

#include "shading/blinn_phong.h"

namespace tandem {

namespace {

bool ranged(const PreparedLight& l) {
  return l.type != LightType::Directional && l.range > 0 && std::isfinite(l.range) &&
         std::isfinite(l.position.x) && std::isfinite(l.position.y) && std::isfinite(l.position.z);
}

Bounds3 sphereBox(const PreparedLight& l) {
  Bounds3 b;
  b.lo = l.position - Vec3(l.range);
  b.hi = l.position + Vec3(l.range);
  return b;
}

bool finite(const Bounds3& b) {
  return std::isfinite(b.lo.x) && std::isfinite(b.lo.y) && std::isfinite(b.lo.z) &&
         std::isfinite(b.hi.x) && std::isfinite(b.hi.y) && std::isfinite(b.hi.z);
}

// More cells than this in one query: every light (a box that large reaches most of them).
constexpr int kMaxQueryCells = 64;
constexpr int kMaxCellsPerAxis = 64;

}  // namespace

std::shared_ptr<const LightCullGrid> LightCullGrid::build(const std::vector<PreparedLight>& lights,
                                                          size_t minLights, size_t maxEntries) {
  if (lights.size() < minLights || lights.size() > size_t(UINT32_MAX)) return nullptr;
  auto g = std::make_shared<LightCullGrid>();
  g->lightCount_ = lights.size();
  Bounds3 region;
  std::vector<float> diameters;
  for (size_t i = 0; i < lights.size(); ++i) {
    if (!ranged(lights[i])) {
      g->everywhere_.push_back(uint32_t(i));
      continue;
    }
    region.extend(sphereBox(lights[i]));
    diameters.push_back(2.0f * lights[i].range);
  }
  if (diameters.empty() || !finite(region)) return nullptr;
  // Cells about as wide as a typical light's sphere: it then overlaps at most 2 x 2 x 2 cells.
  std::nth_element(diameters.begin(), diameters.begin() + std::ptrdiff_t(diameters.size() / 2),
                   diameters.end());
  const float typical = diameters[diameters.size() / 2];
  const Vec3 extent = region.extent();
  const float longest = std::max({extent.x, extent.y, extent.z, 1e-6f});
  float cell = std::max(typical, longest / float(kMaxCellsPerAxis));
  for (;;) {
    for (int a = 0; a < 3; ++a)
      g->dims_[a] = std::clamp(int(std::ceil(extent[a] / cell)), 1, kMaxCellsPerAxis);
    g->origin_ = region.lo;
    g->invCell_ = Vec3(1.0f / cell);
    size_t total = 0;
    for (const PreparedLight& l : lights) {
      if (!ranged(l)) continue;
      int lo[3], hi[3];
      g->cellRange(sphereBox(l), lo, hi);
      total += size_t(hi[0] - lo[0] + 1) * size_t(hi[1] - lo[1] + 1) * size_t(hi[2] - lo[2] + 1);
    }
    const bool single = g->dims_[0] == 1 && g->dims_[1] == 1 && g->dims_[2] == 1;
    if (total <= maxEntries || single) break;
    cell *= 2.0f;  // too many overlaps (lights far larger than most): coarser cells
  }
  const size_t cells = size_t(g->dims_[0]) * size_t(g->dims_[1]) * size_t(g->dims_[2]);
  // Counting sort into per-cell lists; lights go in ascending order, so every list is sorted.
  std::vector<uint32_t> count(cells + 1, 0);
  auto forCells = [&](const PreparedLight& l, auto&& f) {
    int lo[3], hi[3];
    g->cellRange(sphereBox(l), lo, hi);
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x)
          f((size_t(z) * size_t(g->dims_[1]) + size_t(y)) * size_t(g->dims_[0]) + size_t(x));
  };
  for (const PreparedLight& l : lights)
    if (ranged(l)) forCells(l, [&](size_t c) { ++count[c + 1]; });
  for (size_t c = 0; c < cells; ++c) count[c + 1] += count[c];
  g->start_ = count;
  g->entries_.resize(count[cells]);
  for (size_t i = 0; i < lights.size(); ++i)
    if (ranged(lights[i]))
      forCells(lights[i], [&](size_t c) { g->entries_[count[c]++] = uint32_t(i); });
  return g;
}

void LightCullGrid::cellRange(const Bounds3& box, int lo[3], int hi[3]) const {
  auto cellOf = [&](float v, int a) {
    const float t = (v - origin_[a]) * invCell_[a];
    if (!(t >= 0.0f)) return 0;
    if (t >= float(dims_[a])) return dims_[a] - 1;
    return std::min(int(t), dims_[a] - 1);
  };
  for (int a = 0; a < 3; ++a) {
    lo[a] = cellOf(box.lo[a], a);
    hi[a] = cellOf(box.hi[a], a);
  }
}

void LightCullGrid::candidates(const Bounds3& box, std::vector<uint32_t>& out) const {
  out.clear();
  int lo[3], hi[3];
  if (finite(box)) cellRange(box, lo, hi);
  const size_t span = finite(box) ? size_t(hi[0] - lo[0] + 1) * size_t(hi[1] - lo[1] + 1) *
                                        size_t(hi[2] - lo[2] + 1)
                                  : SIZE_MAX;
  if (span > size_t(kMaxQueryCells)) {
    out.resize(lightCount_);
    for (size_t i = 0; i < lightCount_; ++i) out[i] = uint32_t(i);
    return;
  }
  out.assign(everywhere_.begin(), everywhere_.end());
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x) {
        const size_t c = (size_t(z) * size_t(dims_[1]) + size_t(y)) * size_t(dims_[0]) + size_t(x);
        out.insert(out.end(), entries_.begin() + std::ptrdiff_t(start_[c]),
                   entries_.begin() + std::ptrdiff_t(start_[c + 1]));
      }
  std::sort(out.begin(), out.end());
  if (span > 1) out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace tandem
