// Interleaved sampling for depth of field and motion blur (Foster 2015, Aqsis 2.0; Fatahalian et
// al. 2009; Lagae & Dutré 2006): the set T of a frame's N (time, lens) pairs and the sample tiles
// that hand them out.
//
// A tile holds N samples on a regular grid of screen strata (k per pixel, N / k pixels) and uses
// each pair of T exactly once, so a rasterization pass at one pair touches one sample per tile:
// it is bounded by the screen region the primitive covers at that pair. 81 = 3^4 prototype tiles
// have coloured corners (three patterns per corner); a spatial hash colours the vertices of the
// tile grid, so two tiles that share a vertex see the same corner pattern and two that share an
// edge see the same edge pattern (one per pair of end colours).
//
// Exactly-once with shared borders: T is dealt, time-stratified, into fixed subsets, one per
// border position of a tile (the four corner quadrants, the four edge strips) and one for the
// interior. A corner colour chooses how the four quadrant subsets are arranged in the block of
// strata around a vertex; an edge colour pair how the two strip subsets are arranged across an
// edge; each prototype arranges its interior subset. Every arrangement is optimised so that
// samples with similar pairs lie far apart (an energy of Gaussian spatial falloff over pair
// distance, lowered by swaps within a subset), which stratifies the times (and lens positions)
// seen by every pixel filter footprint.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace tandem {

// One pair of T: shutter fraction tau, lens coordinates (u1, u2) in [0,1)^2 (Camera::lensPoint
// maps them onto the disk or n-gon), and a sub-pixel jitter for whole-image methods.
struct TimeLensPair {
  float tau, u1, u2;
  Vec2 jitter;  // in [-0.5, 0.5)^2 (accumulation's anti-aliasing)
};
// N pairs: times stratified over the shutter, lens points stratified over the aperture
// (Hammersley), the two decorrelated by a seeded permutation. `correlated` pairs the i-th time
// with the i-th lens point instead: the compromise of interval methods that strobes.
std::vector<TimeLensPair> stratifiedTimeLensPairs(int n, uint64_t seed, bool correlated = false);

// What "similar pairs" means for the tile optimisation.
enum class PairMetric { Time, Lens, Both };

// The shape of a tile: N pairs, k samples per pixel on an sx x sy grid of strata, tw x th pixels.
struct TileShape {
  int n = 1, k = 1, sx = 1, sy = 1, tw = 1, th = 1;
  int stridesX() const { return tw * sx; }  // strata across a tile
  int stridesY() const { return th * sy; }
};
// The problem with (n, k), or "" when a tile can be built: k >= 1, n >= 1, n a multiple of k,
// n <= 4096.
std::string tileShapeProblem(int n, int k);
// k = sx * sy with sy the largest divisor of k not above sqrt(k); the same for the N / k pixels.
TileShape makeTileShape(int n, int k);

enum class TileKind { Random, ColoredCorner };

struct TileQuality {
  // Smallest screen distance (pixels, between stratum centres) of two samples whose times are
  // equal or neighbours in T (adjacent time strata), over a layout of 12 x 12 tiles.
  double minSimilarTimeDistance = 0;
  // The mean over samples of the distance to the nearest such sample (at most 4 pixels).
  double meanSimilarTimeDistance = 0;
  // Star discrepancy of the times inside each 2 x 2-pixel footprint, mean and worst.
  double meanFootprintDiscrepancy = 0, maxFootprintDiscrepancy = 0;
  // The same for the lens coordinate u1 (how the aperture is covered).
  double meanFootprintLensDiscrepancy = 0;
};

struct TileSet {
  TileShape shape;
  TileKind kind = TileKind::ColoredCorner;
  uint64_t seed = 0;
  static constexpr int kPrototypes = 81;
  // slot[p * n + s]: the pair (index into T) of stratum s (row-major, stridesX wide) of
  // prototype p.
  std::vector<uint16_t> slot;
  // jitter[p * n + s]: the sample's offset inside its stratum, in [0,1)^2.
  std::vector<Vec2> jitter;
  // T's indices sorted by shutter fraction.
  std::vector<uint16_t> timeOrder;
  TileQuality quality;

  // The prototype of tile (tx, ty): its corners' colours c_tl + 3 c_tr + 9 c_bl + 27 c_br, each
  // a hash of the vertex (negative coordinates allowed).
  int prototypeAt(int tx, int ty) const;
  int cornerColor(int vx, int vy) const;
};

// Builds (or returns the cached) tile set for (n, k, kind, metric, seed); `times` gives the
// pairs' shutter fractions and lens coordinates the optimisation separates. Thread-safe.
const TileSet& tileSetFor(int n, int k, TileKind kind, PairMetric metric,
                          const std::vector<TimeLensPair>& pairs, uint64_t seed);
// Builds one without the cache (tests, the experiment's quality table).
TileSet buildTileSet(int n, int k, TileKind kind, PairMetric metric,
                     const std::vector<TimeLensPair>& pairs, uint64_t seed);
// Measures `set` (fills TileSet::quality's fields into the return value).
TileQuality measureTileQuality(const TileSet& set, const std::vector<TimeLensPair>& pairs);

// The border class of stratum (x, y) of a tile: 0-3 corner quadrants (tl, tr, bl, br), 4-7 edge
// strips (top, bottom, left, right), 8 interior. Tiles narrower than 2 strata have no border.
int strataClass(const TileShape& s, int x, int y);

}  // namespace tandem
