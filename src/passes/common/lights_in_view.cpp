#include "passes/common/lights_in_view.h"

#include <tbb/combinable.h>

#include "pipeline/view_tiles.h"
#include "shading/shade_batch.h"

namespace tandem {

std::vector<uint8_t> lightsInView(const std::vector<View>& views, const GBufferReader& g,
                                  const ShadingContext& shading) {
  const size_t n = shading.lights.size();
  tbb::combinable<std::vector<uint8_t>> seen([n] { return std::vector<uint8_t>(n, 0); });
  parallelViewTiles(views, [&](const View&, int x0, int y0, int x1, int y1) {
    Bounds3 box;
    Vec3 p;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        if (g.position(x, y, p)) box.extend(p);
    if (box.empty()) return;
    thread_local std::vector<uint32_t> reaching;
    lightsReaching(shading, box, reaching);
    std::vector<uint8_t>& mine = seen.local();
    for (const uint32_t i : reaching) mine[i] = 1;
  });
  std::vector<uint8_t> all(n, 0);
  seen.combine_each([&](const std::vector<uint8_t>& v) {
    for (size_t i = 0; i < n; ++i) all[i] |= v[i];
  });
  return all;
}

}  // namespace tandem
