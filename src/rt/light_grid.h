// Light selection for next-event estimation among many lights (beyond Peres 2022, whose path tracer
// picks a light uniformly): a uniform grid over the scene's bounds holds, per cell, a
// distribution over the lights proportional to an estimate of each light's unshadowed irradiance
// in the cell. A point light's estimate uses its distance from the cell's centre, never less
// than the cell's half diagonal (so a light inside the cell is not infinitely favoured); it is
// zero only where the light's range cannot reach any point of the cell, so every light that can
// light a point there keeps a probability. The estimator divides by the exact probability of the
// light it picked, so any estimate keeps it unbiased; a better one only lowers the variance.
// With a visibility probe, each estimate is also scaled by the share of a few probe points in
// the cell that see the light, (visible + 1/2) / (probes + 1), so a light the walls hide from a
// room (the sun outside a window) is seldom picked there; the 1/2 keeps every light that can
// reach the cell pickable. The surface's orientation is not part of the estimate.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "core/math.h"
#include "shading/blinn_phong.h"

namespace tandem {

class LightGrid {
 public:
  // Whether light `light` (an index into the lights) is seen from point p.
  using Visibility = std::function<bool(Vec3 p, int light)>;

  // `candidates`: the indices into `lights` the estimator may pick. `bounds`: the region the
  // shaded points lie in (points outside use the nearest cell). At most `cellsPerAxis` cells
  // along the longest axis, fewer where cells x candidates would exceed `maxEntries`.
  // `visible`, when given, is probed from up to `probes` points per cell and light (fewer where
  // the probes would exceed `maxProbes` in all).
  LightGrid(const std::vector<PreparedLight>& lights, std::vector<int> candidates, Bounds3 bounds,
            const Visibility& visible = {}, int cellsPerAxis = 64,
            size_t maxEntries = size_t(1) << 22, int probes = 8,
            size_t maxProbes = size_t(1) << 23);

  struct Pick {
    int light = -1;    // index into the lights, -1 when there are no candidates
    float pdf = 0.0f;  // probability of having picked it
  };
  // Picks a light for a point at `p` with the uniform number u in [0, 1).
  Pick pick(Vec3 p, float u) const;
  // The probability pick() gives the candidate `light` at p (0 when it never picks it).
  float probability(Vec3 p, int light) const;

  int cells(int axis) const { return dims_[axis]; }
  // What pick() reads, for a device copy: the candidates, the grid's box and inverse cell size,
  // and per cell (x fastest) the cumulative distribution over the candidates.
  const std::vector<int>& candidates() const { return candidates_; }
  const Bounds3& bounds() const { return bounds_; }
  Vec3 invCell() const { return invCell_; }
  const std::vector<float>& cdf() const { return cdf_; }
  size_t candidateCount() const { return candidates_.size(); }
  // Probe rays traced while building (0 without a visibility probe).
  size_t probeRays() const { return probeRays_; }

 private:
  size_t cellOf(Vec3 p) const;

  std::vector<int> candidates_;
  Bounds3 bounds_;
  int dims_[3] = {1, 1, 1};
  Vec3 invCell_{0.0f};
  // Per cell, the cumulative distribution over candidates_ (the last entry is 1), or, for a cell
  // no candidate can reach, all zero (uniform then: every candidate contributes nothing there).
  std::vector<float> cdf_;
  size_t probeRays_ = 0;
};

// An identity for a set of prepared lights (and the candidates), to rebuild a cached grid only
// when the lights change.
uint64_t lightSetKey(const std::vector<PreparedLight>& lights, const std::vector<int>& candidates);

}  // namespace tandem
