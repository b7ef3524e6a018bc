// The rasterizer's output: per pixel the nearest triangle (object id, primitive id) and its
// reversed-Z depth. Attributes are resolved once per pixel afterwards, so overdraw never pays
// for them.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tandem {

constexpr uint32_t kNoObject = 0xffffffffu;

struct VisibilityBuffer {
  int width = 0, height = 0;
  std::vector<float> depth;      // reversed-Z: 1 near plane, 0 infinitely far / empty
  std::vector<uint32_t> object;  // kNoObject where nothing was drawn
  std::vector<uint32_t> prim;

  // Allocates without clearing: the rasterizer clears each tile in parallel before drawing it.
  void resize(int w, int h) {
    width = w;
    height = h;
    size_t n = size_t(w) * h;
    depth.resize(n);
    object.resize(n);
    prim.resize(n);
  }
};

}  // namespace tandem
