// The order rt_secondary traces in under a deadline (heuristic `deadline`): work items of one
// 16 x 16 tile and one heuristic node rank (the pixels and effects of that node in that tile),
// most relevant node first, then nearest the view centre, so a node the deadline cuts keeps its
// central part and every effect of a pixel is traced whole or not at all.
#pragma once
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/buffer.h"
#include "passes/heuristic/rt_feedback.h"
#include "scene/view.h"

namespace tandem {

constexpr int kRankedTileSize = 16;
constexpr uint32_t kUnrankedNode = 1u << 20;  // masked pixels of no ranked node: last

// The rank of the node (object, effect) of a pixel, from the heuristic's `heuristic_order`
// (objects x 1, kEffectCount channels, -1 unranked; may be null).
inline uint32_t nodeRank(const Buffer* order, float objectId, int effect) {
  if (!order || objectId < 0) return kUnrankedNode;
  const size_t node = size_t(objectId) * kEffectCount + size_t(effect);
  const float r = node < order->data.size() ? order->data[node] : -1.0f;
  return r >= 0 ? uint32_t(r) : kUnrankedNode;
}

struct RankedTile {
  const View* view;
  int x0, y0, x1, y1;  // frame pixels
  uint32_t rank;       // the node rank this item traces
  uint64_t key;        // rank << 32 | squared distance from the view centre (pixels)
};

// `mask`: the heuristic mask (kEffectCount channels); `ids`: object ids. `prepare(x0, y0, x1,
// y1)` is called once for every tile (in parallel) before it is ranked.
template <class Prepare>
std::vector<RankedTile> rankTiles(const std::vector<View>& views, const Buffer& mask,
                                  const Buffer& ids, const Buffer* order, Prepare&& prepare) {
  constexpr int kTile = kRankedTileSize;
  std::vector<RankedTile> tiles;
  for (const View& v : views)
    for (int y = 0; y < v.height(); y += kTile)
      for (int x = 0; x < v.width(); x += kTile)
        tiles.push_back({&v, v.x + x, v.y + y, v.x + std::min(x + kTile, v.width()),
                         v.y + std::min(y + kTile, v.height()), 0, 0});
  tbb::enumerable_thread_specific<std::vector<RankedTile>> items;
  tbb::parallel_for(size_t(0), tiles.size(), [&](size_t i) {
    const RankedTile& t = tiles[i];
    prepare(t.x0, t.y0, t.x1, t.y1);
    uint32_t ranks[kRankedTileSize * kRankedTileSize * kEffectCount];
    int count = 0;
    for (int y = t.y0; y < t.y1; ++y)
      for (int x = t.x0; x < t.x1; ++x) {
        const float* m = mask.at(x, y);
        for (int e = 0; e < kEffectCount; ++e) {
          if (!(m[e] > 0.5f)) continue;
          const uint32_t r = nodeRank(order, ids.at(x, y)[0], e);
          if (std::find(ranks, ranks + count, r) == ranks + count) ranks[count++] = r;
        }
      }
    const float dx = 0.5f * float(t.x0 + t.x1 - 2 * t.view->x - t.view->width());
    const float dy = 0.5f * float(t.y0 + t.y1 - 2 * t.view->y - t.view->height());
    std::vector<RankedTile>& mine = items.local();
    for (int k = 0; k < count; ++k) {
      RankedTile item = t;
      item.rank = ranks[k];
      item.key = (uint64_t(ranks[k]) << 32) | uint64_t(dx * dx + dy * dy);
      mine.push_back(item);
    }
  });
  std::vector<RankedTile> queue;
  for (const std::vector<RankedTile>& v : items) queue.insert(queue.end(), v.begin(), v.end());
  // Equal keys (two views) in a fixed order: by position.
  std::sort(queue.begin(), queue.end(), [](const RankedTile& a, const RankedTile& b) {
    return a.key != b.key ? a.key < b.key : a.x0 != b.x0 ? a.x0 < b.x0 : a.y0 < b.y0;
  });
  return queue;
}

}  // namespace tandem
