// The samples of one image for interleaved sampling: k per pixel on a grid of strata, each with a
// position and the (time, lens) pair of T it takes, grouped by pair and by cell (a tile's screen
// area) for the rasterizer's and the ray tracer's passes. The sampling schemes compared by Foster
// 2015's experiment differ only in how pairs are handed to strata.
#pragma once
#include <cstdint>
#include <vector>

#include "raster/rasterizer.h"
#include "raster/sample_tiles.h"

namespace tandem {

enum class SamplingScheme {
  Independent,  // each sample a pair of T drawn at random (with replacement), anywhere in its pixel
  Stratified,   // per pixel: its k samples take pairs from k different time strata of T
  RandomTiles,  // interleaved: 81 tiles, each a random permutation of T
  ColoredCorner  // interleaved: 81 optimised colored-corner tiles (sample_tiles.h)
};
const char* schemeName(SamplingScheme s);

struct SampleLayout {
  TileShape shape;
  SamplingScheme scheme = SamplingScheme::ColoredCorner;
  int width = 0, height = 0;                         // pixels
  int cellsX = 0, cellsY = 0;                        // tiles of shape.tw x shape.th pixels
  int stridesW() const { return width * shape.sx; }  // strata across the image
  int stridesH() const { return height * shape.sy; }
  size_t sampleCount() const { return pair.size(); }
  // Per stratum, row-major over stridesW x stridesH: the pair, the position in pixels (inside
  // the stratum) and the same in the rasterizer's 8-bit fixed point.
  std::vector<uint16_t> pair;
  std::vector<Vec2> pos;
  std::vector<int32_t> fx, fy;
  // The samples of pair j in cell c: ids[cellStart[j * (cells + 1) + c] .. + c + 1]; all of
  // pair j: ids[passBegin(j) .. passEnd(j)).
  std::vector<uint32_t> cellStart, ids;
  int cells() const { return cellsX * cellsY; }
  uint32_t passBegin(int j) const { return cellStart[size_t(j) * size_t(cells() + 1)]; }
  uint32_t passEnd(int j) const {
    return cellStart[size_t(j) * size_t(cells() + 1) + size_t(cells())];
  }
  Rasterizer::SampleSet passSamples(int j) const;
  // Every sample, grouped by cell only: allIds[allStart[c] .. allStart[c + 1]).
  std::vector<uint32_t> allStart, allIds;
  Rasterizer::SampleSet allSamples() const;
};

// Lays out a width x height image. `tiles` is used by the tiled schemes (its shape sets k and
// N); `jitter` false puts every sample at its stratum's centre.
SampleLayout buildSampleLayout(SamplingScheme scheme, const TileSet& tiles, int width, int height,
                               uint64_t seed, bool jitter = true);

}  // namespace tandem
