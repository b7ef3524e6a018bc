// Tile-parallel loops over every view's viewport in one dispatch (both eyes of a stereo frame
// share the worker threads). The body gets the view and a tile [x0,x1) x [y0,y1) in frame
// pixels, never straddling two views.
#pragma once
#include <tbb/parallel_for.h>

#include <vector>

#include "core/parallel.h"
#include "scene/view.h"

namespace tandem {

template <class Body>
void parallelViewTiles(const std::vector<View>& views, Body&& body, int tile = kTileSize) {
  if (views.size() == 1) {
    const View& v = views[0];
    parallelTiles(
        v.width(), v.height(),
        [&](int x0, int y0, int x1, int y1) { body(v, x0 + v.x, y0 + v.y, x1 + v.x, y1 + v.y); },
        tile);
    return;
  }
  struct Tile {
    const View* view;
    int x0, y0, x1, y1;
  };
  std::vector<Tile> tiles;
  for (const View& v : views)
    for (int y = 0; y < v.height(); y += tile)
      for (int x = 0; x < v.width(); x += tile)
        tiles.push_back({&v, v.x + x, v.y + y, v.x + std::min(x + tile, v.width()),
                         v.y + std::min(y + tile, v.height())});
  tbb::parallel_for(size_t(0), tiles.size(), [&](size_t i) {
    const Tile& t = tiles[i];
    body(*t.view, t.x0, t.y0, t.x1, t.y1);
  });
}

}  // namespace tandem
