#include "raster/sample_tiles.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <random>
#include <tuple>

#include "core/error.h"
#include "core/hash.h"
#include "core/low_discrepancy.h"

namespace tandem {

std::vector<TimeLensPair> stratifiedTimeLensPairs(int n, uint64_t seed, bool correlated) {
  std::vector<int> perm(static_cast<size_t>(n)), jitterOrder(static_cast<size_t>(n));
  std::iota(perm.begin(), perm.end(), 0);
  std::iota(jitterOrder.begin(), jitterOrder.end(), 0);
  std::mt19937_64 rng(seed ^ 0x5851F42D4C957F2Dull);
  std::shuffle(perm.begin(), perm.end(), rng);
  std::shuffle(jitterOrder.begin(), jitterOrder.end(), rng);
  std::vector<TimeLensPair> pairs(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    // Hammersley point i of n over the lens square; time stratum perm[i] (or i: correlated).
    const Vec2 lens = hammersley(i, n);
    const int stratum = correlated ? i : perm[size_t(i)];
    pairs[size_t(i)] = {(float(stratum) + 0.5f) / float(n), lens.x, lens.y,
                        haltonJitter(1 + jitterOrder[size_t(i)])};
  }
  return pairs;
}

std::string tileShapeProblem(int n, int k) {
  if (k < 1) return "samples per pixel must be at least 1";
  if (n < 1) return "the number of (time, lens) pairs must be at least 1";
  if (n > 4096) return "at most 4096 (time, lens) pairs";
  if (n % k != 0)
    return "the number of (time, lens) pairs (" + std::to_string(n) +
           ") must be a multiple of the samples per pixel (" + std::to_string(k) +
           "): a tile holds each pair once on whole pixels";
  return "";
}

namespace {

// The most square factorisation w x h = m with h <= w.
void squarest(int m, int& w, int& h) {
  h = 1;
  for (int d = 1; d * d <= m; ++d)
    if (m % d == 0) h = d;
  w = m / h;
}

uint64_t mix64(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Corner quadrant (and edge strip) thickness in strata: a quarter of the tile, at least one.
int borderOf(int strata) {
  return strata < 2 ? 0 : std::max(1, strata / 4);
}

}  // namespace

TileShape makeTileShape(int n, int k) {
  const std::string problem = tileShapeProblem(n, k);
  TANDEM_ASSERT(problem.empty());
  TileShape s;
  s.n = n;
  s.k = k;
  squarest(k, s.sx, s.sy);
  squarest(n / k, s.tw, s.th);
  return s;
}

int strataClass(const TileShape& s, int x, int y) {
  const int a = s.stridesX(), b = s.stridesY(), qx = borderOf(a), qy = borderOf(b);
  if (qx == 0 || qy == 0) return 8;
  const int cx = x < qx ? 0 : x >= a - qx ? 2 : 1, cy = y < qy ? 0 : y >= b - qy ? 2 : 1;
  if (cx != 1 && cy != 1) return (cy == 2 ? 2 : 0) + (cx == 2 ? 1 : 0);
  if (cx == 1 && cy != 1) return cy == 0 ? 4 : 5;
  if (cy == 1 && cx != 1) return cx == 0 ? 6 : 7;
  return 8;
}

int TileSet::cornerColor(int vx, int vy) const {
  const uint64_t h = mix64(seed ^ mix64(uint64_t(uint32_t(vx)) | (uint64_t(uint32_t(vy)) << 32)));
  return int(h % 3u);
}

int TileSet::prototypeAt(int tx, int ty) const {
  return cornerColor(tx, ty) + 3 * cornerColor(tx + 1, ty) + 9 * cornerColor(tx, ty + 1) +
         27 * cornerColor(tx + 1, ty + 1);
}

namespace {

// Distance between two pairs under the metric (lens coordinates on the unit square).
struct PairSpace {
  std::vector<float> tau, u1, u2;
  PairMetric metric;
  float dist(int p, int q) const {
    const float dt = tau[size_t(p)] - tau[size_t(q)];
    const float du = u1[size_t(p)] - u1[size_t(q)], dv = u2[size_t(p)] - u2[size_t(q)];
    switch (metric) {
      case PairMetric::Time:
        return std::abs(dt);
      case PairMetric::Lens:
        return std::sqrt(du * du + dv * dv);
      default:
        return std::sqrt(dt * dt + 0.5f * (du * du + dv * dv));
    }
  }
};

// A grid of strata being arranged: cell = pair index or -1 (nothing there); group = the swap
// group of a free cell or -1 (fixed). Energy: sum over cell pairs within the radius of
// w(screen distance) / (pair distance + eps): similar pairs close together cost most.
class Arrangement {
 public:
  Arrangement(int w, int h, const TileShape& shape, const PairSpace& space)
      : w_(w), h_(h), space_(space), cell(size_t(w) * h, -1), group(size_t(w) * h, -1) {
    // Gaussian falloff over screen distance in pixels (sigma 0.7 px: a pixel filter's reach).
    const float sigma = 1.0f, radius = 2.5f * sigma;
    rx_ = std::max(1, int(std::ceil(radius * float(shape.sx))));
    ry_ = std::max(1, int(std::ceil(radius * float(shape.sy))));
    weights_.resize(size_t(2 * rx_ + 1) * (2 * ry_ + 1));
    for (int dy = -ry_; dy <= ry_; ++dy)
      for (int dx = -rx_; dx <= rx_; ++dx) {
        const float px = float(dx) / float(shape.sx), py = float(dy) / float(shape.sy);
        const float d2 = px * px + py * py;
        weights_[size_t(dy + ry_) * (2 * rx_ + 1) + size_t(dx + rx_)] =
            d2 > radius * radius ? 0.0f : std::exp(-d2 / (2 * sigma * sigma));
      }
    eps_ = 0.5f / float(space.tau.size());
  }

  // Energy of pair p sitting at (x, y), against every other filled cell in reach (except the
  // cell `skip`).
  float energyAt(int x, int y, int p, int skip) const {
    float e = 0;
    for (int dy = -ry_; dy <= ry_; ++dy) {
      const int yy = y + dy;
      if (yy < 0 || yy >= h_) continue;
      for (int dx = -rx_; dx <= rx_; ++dx) {
        const int xx = x + dx;
        if (xx < 0 || xx >= w_ || (dx == 0 && dy == 0)) continue;
        const int i = yy * w_ + xx;
        const int q = cell[size_t(i)];
        if (q < 0 || i == skip) continue;
        const float wgt = weights_[size_t(dy + ry_) * (2 * rx_ + 1) + size_t(dx + rx_)];
        if (wgt > 0) e += wgt / (space_.dist(p, q) + eps_);
      }
    }
    return e;
  }

  // Swaps within groups while they lower the energy (`rounds` attempts per free cell).
  void optimise(std::mt19937_64& rng, int rounds) {
    std::vector<std::vector<int>> members;
    for (size_t i = 0; i < group.size(); ++i)
      if (group[i] >= 0) {
        if (size_t(group[i]) >= members.size()) members.resize(size_t(group[i]) + 1);
        members[size_t(group[i])].push_back(int(i));
      }
    std::vector<int> free;
    for (const auto& m : members)
      if (m.size() >= 2) free.insert(free.end(), m.begin(), m.end());
    if (free.empty()) return;
    const size_t attempts = size_t(rounds) * free.size();
    for (size_t t = 0; t < attempts; ++t) {
      const int i = free[rng() % free.size()];
      const auto& m = members[size_t(group[size_t(i)])];
      const int j = m[rng() % m.size()];
      if (i == j) continue;
      const int xi = i % w_, yi = i / w_, xj = j % w_, yj = j / w_;
      const int pi = cell[size_t(i)], pj = cell[size_t(j)];
      const float before = energyAt(xi, yi, pi, j) + energyAt(xj, yj, pj, i);
      const float after = energyAt(xi, yi, pj, j) + energyAt(xj, yj, pi, i);
      if (after < before) std::swap(cell[size_t(i)], cell[size_t(j)]);
    }
  }

  int w_, h_;
  const PairSpace& space_;
  std::vector<int> cell, group;

 private:
  int rx_ = 1, ry_ = 1;
  std::vector<float> weights_;
  float eps_ = 0;
};

}  // namespace

namespace {

// The colored-corner construction: T dealt into pools per border class, then corner blocks,
// edge strips and the 81 prototypes arranged and optimised in turn (one generator throughout,
// so a seed gives one set).
class ColoredCornerBuilder {
 public:
  ColoredCornerBuilder(TileSet& set, const std::vector<TimeLensPair>& pairs_in, PairMetric metric,
                       std::mt19937_64& rng)
      : set_(set), s(set.shape), pairs(pairs_in), n(int(pairs_in.size())), rng_(rng) {
    a = s.stridesX(), b = s.stridesY(), qx = borderOf(a), qy = borderOf(b);
    space.metric = metric;
    for (const TimeLensPair& p : pairs_in) {
      space.tau.push_back(p.tau);
      space.u1.push_back(p.u1);
      space.u2.push_back(p.u2);
    }
  }
  void build() {
    dealPools();
    if (qx > 0 && qy > 0) {
      cornerBlocks();
      edgeStrips();
    }
    prototypes();
  }

 private:
  void dealPools() {
    // Pools: T dealt, in time order, into one pool per border class (so every region spans the
    // whole shutter). A border region of one tile never shares a pair with another, and the
    // interior takes whatever its borders left, so border pools may be larger than their regions:
    // the interior's strata are spent first on corners (up to three choices per stratum, one per
    // colour), then on edges, and each colour (pair) picks its region's pairs from the pool.
    for (int y = 0; y < b; ++y)
      for (int x = 0; x < a; ++x) ++classSize[strataClass(s, x, y)];
    int poolSize[9];
    {
      int spare = classSize[8];
      for (int first : {0, 4})  // corners, then edges
        for (int c = first; c < first + 4; ++c) {
          const int extra = std::min(2 * classSize[c], spare / (first + 4 - c));
          poolSize[c] = classSize[c] + extra;
          spare -= extra;
        }
      poolSize[8] = spare;
    }
    std::vector<int> byTime(static_cast<size_t>(n));
    std::iota(byTime.begin(), byTime.end(), 0);
    std::stable_sort(byTime.begin(), byTime.end(),
                     [&](int i, int j) { return pairs[size_t(i)].tau < pairs[size_t(j)].tau; });
    for (int r = 0; r < n; ++r) {
      int best = -1;
      double bestDeficit = -1e30;
      for (int c = 0; c < 9; ++c) {
        if (int(pool[c].size()) >= poolSize[c]) continue;
        const double deficit = double(poolSize[c]) * (r + 1) / n - double(pool[c].size());
        if (deficit > bestDeficit) {
          bestDeficit = deficit;
          best = c;
        }
      }
      pool[best].push_back(byTime[size_t(r)]);
    }
  }
  // The pairs of border class c for colour key `key`: one from each of classSize[c] consecutive
  // time strata of the pool, the choice inside a stratum turning with the key.
  std::vector<int> subsetFor(int c, int key) const {
    std::vector<int> out;
    const int m = classSize[c], p = int(pool[c].size());
    for (int i = 0; i < m; ++i) {
      const int lo = i * p / m, hi = (i + 1) * p / m;
      out.push_back(pool[c][size_t(lo + (key + i) % (hi - lo))]);
    }
    return out;
  }
  // Fills `cells` of `arr` with a shuffle of `pick`, as swap group g.
  void seedGroup(Arrangement& arr, const std::vector<int>& cells, std::vector<int> pick, int g) {
    std::shuffle(pick.begin(), pick.end(), rng_);
    TANDEM_ASSERT(pick.size() == cells.size());
    for (size_t i = 0; i < cells.size(); ++i) {
      arr.cell[size_t(cells[i])] = pick[i];
      arr.group[size_t(cells[i])] = g;
    }
  }
  void cornerBlocks() {
    // Corner blocks (2qx x 2qy strata around a vertex): quadrants br | bl over tr | tl.
    for (int c = 0; c < 3; ++c) {
      Arrangement arr(2 * qx, 2 * qy, s, space);
      std::vector<int> cells[4];
      for (int y = 0; y < 2 * qy; ++y)
        for (int x = 0; x < 2 * qx; ++x) {
          const int cls = (y < qy ? 2 : 0) + (x < qx ? 1 : 0);  // which tile's quadrant
          cells[cls].push_back(y * 2 * qx + x);
        }
      for (int cls = 0; cls < 4; ++cls) seedGroup(arr, cells[cls], subsetFor(cls, c), cls);
      arr.optimise(rng_, rounds);
      block[size_t(c)] = arr.cell;
    }
  }
  void edgeStrips() {
    // Edge strips, with the corner blocks of their end colours fixed beside them. Horizontal
    // (c1 left, c2 right): 2qy rows, the upper tile's bottom strip over the lower tile's top strip.
    // Vertical (c1 top, c2 bottom): the left tile's right strip beside the right tile's left strip.
    const int ew = a - 2 * qx, eh = b - 2 * qy;
    for (int c1 = 0; c1 < 3; ++c1)
      for (int c2 = 0; c2 < 3; ++c2) {
        if (ew > 0) {
          Arrangement arr(a, 2 * qy, s, space);
          std::vector<int> top, bottom;
          for (int y = 0; y < 2 * qy; ++y)
            for (int x = 0; x < a; ++x) {
              if (x < qx)
                arr.cell[size_t(y * a + x)] = block[size_t(c1)][size_t(y * 2 * qx + qx + x)];
              else if (x >= a - qx)
                arr.cell[size_t(y * a + x)] = block[size_t(c2)][size_t(y * 2 * qx + x - (a - qx))];
              else
                (y < qy ? bottom : top).push_back(y * a + x);
            }
          seedGroup(arr, bottom, subsetFor(5, c1 + 3 * c2), 5);
          seedGroup(arr, top, subsetFor(4, c1 + 3 * c2), 4);
          arr.optimise(rng_, rounds);
          auto& e = hEdge[size_t(c1 + 3 * c2)];
          for (int y = 0; y < 2 * qy; ++y)
            for (int x = qx; x < a - qx; ++x) e.push_back(arr.cell[size_t(y * a + x)]);
        }
        if (eh > 0) {
          Arrangement arr(2 * qx, b, s, space);
          std::vector<int> left, right;
          for (int y = 0; y < b; ++y)
            for (int x = 0; x < 2 * qx; ++x) {
              if (y < qy)
                arr.cell[size_t(y * 2 * qx + x)] = block[size_t(c1)][size_t((qy + y) * 2 * qx + x)];
              else if (y >= b - qy)
                arr.cell[size_t(y * 2 * qx + x)] =
                    block[size_t(c2)][size_t((y - (b - qy)) * 2 * qx + x)];
              else
                (x < qx ? right : left).push_back(y * 2 * qx + x);
            }
          seedGroup(arr, right, subsetFor(7, c1 + 3 * c2), 7);
          seedGroup(arr, left, subsetFor(6, c1 + 3 * c2), 6);
          arr.optimise(rng_, rounds);
          auto& e = vEdge[size_t(c1 + 3 * c2)];
          for (int y = qy; y < b - qy; ++y)
            for (int x = 0; x < 2 * qx; ++x) e.push_back(arr.cell[size_t(y * 2 * qx + x)]);
        }
      }
  }
  void prototypes() {
    // Prototypes: borders from the patterns of their corner colours, the interior optimised.
    for (int p = 0; p < TileSet::kPrototypes; ++p) {
      const int ctl = p % 3, ctr = (p / 3) % 3, cbl = (p / 9) % 3, cbr = (p / 27) % 3;
      Arrangement arr(a, b, s, space);
      std::vector<int> interior;
      const int ew = a - 2 * qx;
      for (int y = 0; y < b; ++y)
        for (int x = 0; x < a; ++x) {
          const int i = y * a + x;
          int& v = arr.cell[size_t(i)];
          switch (strataClass(s, x, y)) {
            case 0:
              v = block[size_t(ctl)][size_t((qy + y) * 2 * qx + qx + x)];
              break;
            case 1:
              v = block[size_t(ctr)][size_t((qy + y) * 2 * qx + x - (a - qx))];
              break;
            case 2:
              v = block[size_t(cbl)][size_t((y - (b - qy)) * 2 * qx + qx + x)];
              break;
            case 3:
              v = block[size_t(cbr)][size_t((y - (b - qy)) * 2 * qx + x - (a - qx))];
              break;
            case 4:  // top strip: the lower rows of the edge between tl and tr
              v = hEdge[size_t(ctl + 3 * ctr)][size_t((qy + y) * ew + x - qx)];
              break;
            case 5:  // bottom strip: the upper rows of the edge between bl and br
              v = hEdge[size_t(cbl + 3 * cbr)][size_t((y - (b - qy)) * ew + x - qx)];
              break;
            case 6:  // left strip: the right-hand columns of the edge between tl and bl
              v = vEdge[size_t(ctl + 3 * cbl)][size_t((y - qy) * 2 * qx + qx + x)];
              break;
            case 7:
              v = vEdge[size_t(ctr + 3 * cbr)][size_t((y - qy) * 2 * qx + x - (a - qx))];
              break;
            default:
              interior.push_back(i);
          }
        }
      std::vector<char> used(size_t(n), 0);
      for (int v : arr.cell)
        if (v >= 0) used[size_t(v)] = 1;
      std::vector<int> rest;
      for (int j = 0; j < n; ++j)
        if (!used[size_t(j)]) rest.push_back(j);
      seedGroup(arr, interior, rest, 8);
      arr.optimise(rng_, rounds);
      for (int i = 0; i < n; ++i)
        set_.slot[size_t(p) * n + size_t(i)] = uint16_t(arr.cell[size_t(i)]);
    }
  }

  static constexpr int rounds = 40;
  TileSet& set_;
  const TileShape& s;
  const std::vector<TimeLensPair>& pairs;
  int n, a = 0, b = 0, qx = 0, qy = 0;
  std::mt19937_64& rng_;
  PairSpace space;
  int classSize[9] = {};
  std::vector<int> pool[9];
  std::vector<std::vector<int>> block = std::vector<std::vector<int>>(3);
  std::vector<std::vector<int>> hEdge = std::vector<std::vector<int>>(9), vEdge = hEdge;
};

}  // namespace

TileSet buildTileSet(int n, int k, TileKind kind, PairMetric metric,
                     const std::vector<TimeLensPair>& pairs, uint64_t seed) {
  TANDEM_ASSERT(int(pairs.size()) == n);
  TileSet set;
  set.shape = makeTileShape(n, k);
  set.kind = kind;
  set.seed = seed;
  const int P = TileSet::kPrototypes;
  set.slot.assign(size_t(P) * n, 0);
  set.jitter.resize(size_t(P) * n);
  std::mt19937_64 rng(mix64(seed ^ 0xC0FFEEull) ^ uint64_t(n) * 31 ^ uint64_t(k));
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  for (auto& j : set.jitter) {
    j.x = std::min(uni(rng), 0.99999994f);
    j.y = std::min(uni(rng), 0.99999994f);
  }

  set.timeOrder.resize(size_t(n));
  std::iota(set.timeOrder.begin(), set.timeOrder.end(), uint16_t(0));
  std::stable_sort(set.timeOrder.begin(), set.timeOrder.end(),
                   [&](int i, int j) { return pairs[size_t(i)].tau < pairs[size_t(j)].tau; });

  if (kind == TileKind::Random) {
    std::vector<uint16_t> perm(static_cast<size_t>(n));
    std::iota(perm.begin(), perm.end(), uint16_t(0));
    for (int p = 0; p < P; ++p) {
      std::shuffle(perm.begin(), perm.end(), rng);
      std::copy(perm.begin(), perm.end(), set.slot.begin() + ptrdiff_t(p) * n);
    }
    set.quality = measureTileQuality(set, pairs);
    return set;
  }

  ColoredCornerBuilder(set, pairs, metric, rng).build();
  set.quality = measureTileQuality(set, pairs);
  return set;
}

TileQuality measureTileQuality(const TileSet& set, const std::vector<TimeLensPair>& pairs) {
  const TileShape& s = set.shape;
  const int tiles = 12, a = s.stridesX(), b = s.stridesY();
  const int W = tiles * a, H = tiles * b;  // strata
  std::vector<int> pairAt(size_t(W) * H);
  std::vector<Vec2> pos(size_t(W) * H);
  for (int ty = 0; ty < tiles; ++ty)
    for (int tx = 0; tx < tiles; ++tx) {
      const int p = set.prototypeAt(tx, ty);
      for (int y = 0; y < b; ++y)
        for (int x = 0; x < a; ++x) {
          const size_t i = size_t(ty * b + y) * W + size_t(tx * a + x);
          const size_t slot = size_t(p) * s.n + size_t(y * a + x);
          pairAt[i] = set.slot[slot];
          // Stratum centres: the arrangement's quality, not the jitter's.
          pos[i] = {(float(tx * a + x) + 0.5f) / float(s.sx),
                    (float(ty * b + y) + 0.5f) / float(s.sy)};
        }
    }
  // Time ranks: similar times are equal or adjacent ranks.
  std::vector<int> rank(size_t(s.n));
  {
    std::vector<int> order(size_t(s.n));
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](int i, int j) { return pairs[size_t(i)].tau < pairs[size_t(j)].tau; });
    for (int r = 0; r < s.n; ++r) rank[size_t(order[size_t(r)])] = r;
  }
  TileQuality q;
  double minD = 1e30, sumNearest = 0;
  const int reachX = 4 * s.sx, reachY = 4 * s.sy;  // 4 pixels
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const size_t i = size_t(y) * W + size_t(x);
      double nearest = 4.0;
      for (int yy = std::max(0, y - reachY); yy <= std::min(H - 1, y + reachY); ++yy)
        for (int xx = std::max(0, x - reachX); xx <= std::min(W - 1, x + reachX); ++xx) {
          const size_t j = size_t(yy) * W + size_t(xx);
          if (j == i) continue;
          if (std::abs(rank[size_t(pairAt[i])] - rank[size_t(pairAt[j])]) > 1) continue;
          const float dx = pos[i].x - pos[j].x, dy = pos[i].y - pos[j].y;
          nearest = std::min(nearest, double(std::sqrt(dx * dx + dy * dy)));
        }
      minD = std::min(minD, nearest);
      sumNearest += nearest;
    }
  q.meanSimilarTimeDistance = sumNearest / double(size_t(W) * H);
  q.minSimilarTimeDistance = minD > 1e29 ? 4.0 : minD;
  // Footprints of 2 x 2 pixels, every pixel position.
  auto star = [](std::vector<float>& v) {
    std::sort(v.begin(), v.end());
    const double n = double(v.size());
    double d = 0;
    for (size_t i = 0; i < v.size(); ++i)
      d = std::max({d, double(i + 1) / n - v[i], double(v[i]) - double(i) / n});
    return d;
  };
  const int pw = W / s.sx, ph = H / s.sy;
  double sumT = 0, maxT = 0, sumL = 0;
  int count = 0;
  std::vector<float> t, l;
  for (int py = 0; py + 2 <= ph; ++py)
    for (int px = 0; px + 2 <= pw; ++px) {
      t.clear();
      l.clear();
      for (int y = py * s.sy; y < (py + 2) * s.sy; ++y)
        for (int x = px * s.sx; x < (px + 2) * s.sx; ++x) {
          const int p = pairAt[size_t(y) * W + size_t(x)];
          t.push_back(pairs[size_t(p)].tau);
          l.push_back(pairs[size_t(p)].u1);
        }
      const double dt = star(t);
      sumT += dt;
      maxT = std::max(maxT, dt);
      sumL += star(l);
      ++count;
    }
  q.meanFootprintDiscrepancy = sumT / std::max(count, 1);
  q.maxFootprintDiscrepancy = maxT;
  q.meanFootprintLensDiscrepancy = sumL / std::max(count, 1);
  return q;
}

const TileSet& tileSetFor(int n, int k, TileKind kind, PairMetric metric,
                          const std::vector<TimeLensPair>& pairs, uint64_t seed) {
  static std::mutex mutex;
  static std::map<uint64_t, std::unique_ptr<TileSet>> cache;
  Hasher h;
  h.pod(n).pod(k).pod(int(kind)).pod(int(metric)).pod(seed);
  for (const TimeLensPair& p : pairs) h.pod(p.tau).pod(p.u1).pod(p.u2);
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[h.value()];
  if (!slot) slot = std::make_unique<TileSet>(buildTileSet(n, k, kind, metric, pairs, seed));
  return *slot;
}

}  // namespace tandem
