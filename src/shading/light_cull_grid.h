// Which lights can reach a region, found without visiting every light: a uniform grid over the
// union of the range-limited lights' spheres lists, per cell, the lights whose sphere overlaps
// it; lights without a range (directional, point and spot without `range`) reach everywhere and
// are listed once. Shading a point or a batch then costs what the lights reaching it cost, not
// what the scene's lights cost (a thousand small lights in a room). The lists are a superset:
// callers keep their exact per-light test (shade_batch.h's lightsReaching), so no image changes.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "core/math.h"

namespace tandem {

struct PreparedLight;

class LightCullGrid {
 public:
  // Null when no light has a range (nothing to cull), or for fewer than `minLights` lights.
  static std::shared_ptr<const LightCullGrid> build(const std::vector<PreparedLight>& lights,
                                                    size_t minLights = 16,
                                                    size_t maxEntries = size_t(1) << 22);

  // Appends to `out` (cleared first) the indices, ascending and unique, of every light that may
  // reach some point of `box`: all those whose sphere overlaps the box's cells, and every light
  // without a range. A box that is not finite, or spans many cells, gets every light.
  void candidates(const Bounds3& box, std::vector<uint32_t>& out) const;

  int cells(int axis) const { return dims_[axis]; }
  size_t entries() const { return entries_.size(); }

 private:
  // The cell range [lo, hi] a box covers along each axis, clamped to the grid (monotone in the
  // coordinates, so a sphere overlapping a box shares a cell with it even outside the grid).
  void cellRange(const Bounds3& box, int lo[3], int hi[3]) const;

  size_t lightCount_ = 0;
  Vec3 origin_{0.0f}, invCell_{0.0f};
  int dims_[3] = {1, 1, 1};
  std::vector<uint32_t> everywhere_;  // lights without a range, ascending
  std::vector<uint32_t> start_;       // per cell, its first entry (cells + 1 values)
  std::vector<uint32_t> entries_;     // per cell, the ranged lights overlapping it, ascending
};

}  // namespace tandem
