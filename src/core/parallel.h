// Tile-parallel loops over an image, written once (oneTBB). The body gets a tile rectangle
// [x0,x1) x [y0,y1) and is called once per tile, never per pixel.
#pragma once
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>

namespace tandem {

constexpr int kTileSize = 32;

template <class Body>
void parallelTiles(int width, int height, Body&& body, int tile = kTileSize) {
  tbb::parallel_for(tbb::blocked_range2d<int>(0, height, tile, 0, width, tile),
                    [&](const tbb::blocked_range2d<int>& r) {
                      body(r.cols().begin(), r.rows().begin(), r.cols().end(), r.rows().end());
                    });
}

template <class Body>
void parallelRange(size_t n, Body&& body, size_t grain = 1024) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, grain),
                    [&](const tbb::blocked_range<size_t>& r) { body(r.begin(), r.end()); });
}

// body(begin, end) once per fixed block [k block, (k + 1) block) of [0, n) (the last one
// shorter), blocks in parallel. parallelRange's chunks end where the scheduler split the range,
// differently from run to run; these blocks are the same every run, so work grouped within one
// (8-wide packets and shading batches) and its floating-point results are deterministic.
template <class Body>
void parallelBlocks(size_t n, size_t block, Body&& body) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, (n + block - 1) / block),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t k = r.begin(); k < r.end(); ++k)
                        body(k * block, std::min(n, (k + 1) * block));
                    });
}

// body(y) once per row y in [0, height), rows handed out in groups of `grain`.
template <class Body>
void parallelRows(int height, Body&& body, int grain = 4) {
  tbb::parallel_for(tbb::blocked_range<int>(0, height, grain),
                    [&](const tbb::blocked_range<int>& r) {
                      for (int y = r.begin(); y < r.end(); ++y) body(y);
                    });
}

}  // namespace tandem
