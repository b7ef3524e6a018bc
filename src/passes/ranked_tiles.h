// The order rt_secondary traces in under a deadline (heuristic `deadline`): 16 x 16 tiles that
// hold masked pixels, most relevant first (the best rank among the nodes of their masked pixels),
// then nearest the view centre, so an object the deadline cuts keeps its central part.
#pragma once
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/buffer.h"
#include "passes/rt_stats.h"
#include "scene/view.h"

namespace tandem {

struct RankedTile {
  const View* view;
  int x0, y0, x1, y1;  // frame pixels
  uint64_t key;        // rank << 32 | squared distance from the view centre (pixels)
};

constexpr int kRankedTileSize = 16;
constexpr uint64_t kUnrankedNode = 1u << 20;  // masked pixels of no ranked node: last

// `mask`: the heuristic mask (kEffectCount channels); `ids`: object ids; `order`: the heuristic's
// ranks (objects x 1, kEffectCount channels, -1 unranked; may be null). Tiles with nothing masked
// are not returned: `empty(x0, y0, x1, y1)` is called for each of them instead (in parallel).
template <class Empty>
std::vector<RankedTile> rankTiles(const std::vector<View>& views, const Buffer& mask,
                                  const Buffer& ids, const Buffer* order, Empty&& empty) {
  constexpr int kTile = kRankedTileSize;
  std::vector<RankedTile> tiles;
  for (const View& v : views)
    for (int y = 0; y < v.height(); y += kTile)
      for (int x = 0; x < v.width(); x += kTile)
        tiles.push_back({&v, v.x + x, v.y + y, v.x + std::min(x + kTile, v.width()),
                         v.y + std::min(y + kTile, v.height()), ~0ull});
  tbb::parallel_for(size_t(0), tiles.size(), [&](size_t i) {
    RankedTile& t = tiles[i];
    uint64_t rank = ~0ull;
    for (int y = t.y0; y < t.y1; ++y)
      for (int x = t.x0; x < t.x1; ++x) {
        const float* m = mask.at(x, y);
        const float id = ids.at(x, y)[0];
        for (int e = 0; e < kEffectCount; ++e) {
          if (!(m[e] > 0.5f)) continue;
          const size_t node = size_t(id) * kEffectCount + size_t(e);
          const float r = order && id >= 0 && node < order->data.size() ? order->data[node] : -1;
          rank = std::min(rank, r >= 0 ? uint64_t(r) : kUnrankedNode);
        }
      }
    if (rank == ~0ull) {
      empty(t.x0, t.y0, t.x1, t.y1);
      return;
    }
    const float dx = 0.5f * float(t.x0 + t.x1 - 2 * t.view->x - t.view->width());
    const float dy = 0.5f * float(t.y0 + t.y1 - 2 * t.view->y - t.view->height());
    t.key = (rank << 32) | uint64_t(dx * dx + dy * dy);
  });
  tiles.erase(std::remove_if(tiles.begin(), tiles.end(),
                             [](const RankedTile& t) { return t.key == ~0ull; }),
              tiles.end());
  std::sort(tiles.begin(), tiles.end(),
            [](const RankedTile& a, const RankedTile& b) { return a.key < b.key; });
  return tiles;
}

}  // namespace tandem
