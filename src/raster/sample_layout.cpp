#include "raster/sample_layout.h"

#include <algorithm>
#include <numeric>
#include <random>

namespace tandem {

const char* schemeName(SamplingScheme s) {
  switch (s) {
    case SamplingScheme::Independent:
      return "independent";
    case SamplingScheme::Stratified:
      return "stratified";
    case SamplingScheme::RandomTiles:
      return "random_tiles";
    default:
      return "colored_corner";
  }
}

Rasterizer::SampleSet SampleLayout::passSamples(int j) const {
  Rasterizer::SampleSet s;
  s.cellW = shape.tw;
  s.cellH = shape.th;
  s.cellsX = cellsX;
  s.cellsY = cellsY;
  s.start = cellStart.data() + size_t(j) * size_t(cells() + 1);
  s.ids = ids.data();
  s.pos = pos.data();
  s.fx = fx.data();
  s.fy = fy.data();
  return s;
}

Rasterizer::SampleSet SampleLayout::allSamples() const {
  Rasterizer::SampleSet s = passSamples(0);
  s.start = allStart.data();
  s.ids = allIds.data();
  return s;
}

SampleLayout buildSampleLayout(SamplingScheme scheme, const TileSet& tiles, int width, int height,
                               uint64_t seed, bool jitter) {
  SampleLayout L;
  L.shape = tiles.shape;
  L.scheme = scheme;
  L.width = width;
  L.height = height;
  const TileShape& s = L.shape;
  const int n = s.n, a = s.stridesX(), b = s.stridesY();
  L.cellsX = (width + s.tw - 1) / s.tw;
  L.cellsY = (height + s.th - 1) / s.th;
  const int SW = L.stridesW(), SH = L.stridesH();
  const size_t count = size_t(SW) * size_t(SH);
  L.pair.resize(count);
  L.pos.resize(count);
  L.fx.resize(count);
  L.fy.resize(count);
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + 0x1234567ull);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  auto unit = [&] { return std::min(uni(rng), 0.99999994f); };

  // Stratified per pixel: T in time order cut into k groups, one per sample of a pixel.
  std::vector<int> groupOrder(size_t(s.k));
  std::iota(groupOrder.begin(), groupOrder.end(), 0);

  for (int y = 0; y < SH; ++y)
    for (int x = 0; x < SW; ++x) {
      const size_t i = size_t(y) * size_t(SW) + size_t(x);
      Vec2 j{0.5f, 0.5f};
      switch (scheme) {
        case SamplingScheme::Independent:
          L.pair[i] = uint16_t(rng() % uint64_t(n));
          if (jitter) j = {unit(), unit()};
          // Anywhere in the pixel, not its stratum.
          L.pos[i] = {float(x / s.sx) + (jitter ? unit() : (float(x % s.sx) + 0.5f) / float(s.sx)),
                      float(y / s.sy) + (jitter ? unit() : (float(y % s.sy) + 0.5f) / float(s.sy))};
          break;
        case SamplingScheme::Stratified:
          // Filled per pixel below.
          break;
        default: {
          const int tx = x / a, ty = y / b;
          const int p = tiles.prototypeAt(tx, ty);
          const size_t slot = size_t(p) * size_t(n) + size_t((y - ty * b) * a + (x - tx * a));
          L.pair[i] = tiles.slot[slot];
          if (jitter) j = tiles.jitter[slot];
        }
      }
      if (scheme != SamplingScheme::Independent)
        L.pos[i] = {(float(x) + j.x) / float(s.sx), (float(y) + j.y) / float(s.sy)};
    }
  if (scheme == SamplingScheme::Stratified) {
    const int groupSize = n / s.k;
    for (int py = 0; py < height; ++py)
      for (int px = 0; px < width; ++px) {
        std::shuffle(groupOrder.begin(), groupOrder.end(), rng);
        for (int k = 0; k < s.k; ++k) {
          const int x = px * s.sx + k % s.sx, y = py * s.sy + k / s.sx;
          const size_t i = size_t(y) * size_t(SW) + size_t(x);
          const int g = groupOrder[size_t(k)];
          L.pair[i] =
              uint16_t(tiles.timeOrder[size_t(g * groupSize) + rng() % uint64_t(groupSize)]);
          const Vec2 j = jitter ? Vec2{unit(), unit()} : Vec2{0.5f, 0.5f};
          L.pos[i] = {(float(x) + j.x) / float(s.sx), (float(y) + j.y) / float(s.sy)};
        }
      }
  }
  for (size_t i = 0; i < count; ++i) {
    L.fx[i] = int32_t(L.pos[i].x * 256.0f + 0.5f);
    L.fy[i] = int32_t(L.pos[i].y * 256.0f + 0.5f);
  }

  // Group by pair, then by cell (counting sort).
  const int cells = L.cells();
  L.cellStart.assign(size_t(n) * size_t(cells + 1), 0);
  std::vector<uint32_t> counts(size_t(n) * size_t(cells), 0);
  auto cellOf = [&](size_t i) {
    const int x = int(i % size_t(SW)) / s.sx / s.tw, y = int(i / size_t(SW)) / s.sy / s.th;
    return size_t(y) * size_t(L.cellsX) + size_t(x);
  };
  for (size_t i = 0; i < count; ++i) ++counts[size_t(L.pair[i]) * size_t(cells) + cellOf(i)];
  uint32_t running = 0;
  for (int j = 0; j < n; ++j) {
    for (int c = 0; c < cells; ++c) {
      L.cellStart[size_t(j) * size_t(cells + 1) + size_t(c)] = running;
      running += counts[size_t(j) * size_t(cells) + size_t(c)];
    }
    L.cellStart[size_t(j) * size_t(cells + 1) + size_t(cells)] = running;
  }
  L.ids.resize(count);
  std::vector<uint32_t> fill(size_t(n) * size_t(cells));
  for (int j = 0; j < n; ++j)
    for (int c = 0; c < cells; ++c)
      fill[size_t(j) * size_t(cells) + size_t(c)] =
          L.cellStart[size_t(j) * size_t(cells + 1) + size_t(c)];
  for (size_t i = 0; i < count; ++i)
    L.ids[fill[size_t(L.pair[i]) * size_t(cells) + cellOf(i)]++] = uint32_t(i);
  // By cell alone.
  L.allStart.assign(size_t(cells) + 1, 0);
  for (size_t i = 0; i < count; ++i) ++L.allStart[cellOf(i) + 1];
  for (int c = 0; c < cells; ++c) L.allStart[size_t(c) + 1] += L.allStart[size_t(c)];
  L.allIds.resize(count);
  std::vector<uint32_t> at(L.allStart.begin(), L.allStart.end() - 1);
  for (size_t i = 0; i < count; ++i) L.allIds[at[cellOf(i)]++] = uint32_t(i);
  return L;
}

}  // namespace tandem
