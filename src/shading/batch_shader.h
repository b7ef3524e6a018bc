// Tiled deferred shading of a stream of pixels: lanes are filled one pixel at a time and the batch
// is shaded into an RGB buffer whenever it is full (each batch evaluates only the lights that can
// reach it). Deferred shading, shading from the visibility buffer and reflection probes all
// shade this way.
#pragma once
#include <vector>

#include "core/buffer.h"
#include "shading/shade_batch.h"

namespace tandem {

class BatchShader {
 public:
  BatchShader(const ShadingContext& ctx, Buffer& out) : ctx_(ctx), out_(out) {}
  ~BatchShader() { flush(); }
  BatchShader(const BatchShader&) = delete;
  BatchShader& operator=(const BatchShader&) = delete;

  // The lane to fill next, then push() its pixel.
  ShadeBatch& batch() { return b_; }
  int lane() const { return b_.count; }
  void push(int x, int y) {
    xs_[b_.count] = x;
    ys_[b_.count++] = y;
    if (b_.count == ShadeBatch::kMax) flush();
  }
  // A whole batch filled at once (lane() was 0) from the n pixels (x .. x + n - 1, y), whose
  // positions lie in `lanes`; shaded right away.
  void pushSpan(int x, int y, int n, const Bounds3& lanes) {
    b_.count = n;
    shade(&lanes);
    float* o = out_.at(x, y);
    for (int k = 0; k < n; ++k, o += 3)
      o[0] = b_.f[ShadeBatch::OR][k], o[1] = b_.f[ShadeBatch::OG][k],
      o[2] = b_.f[ShadeBatch::OB][k];
    b_.count = 0;
  }
  void flush() {
    if (b_.count == 0) return;
    shade();
    for (int k = 0; k < b_.count; ++k) out_.setRgb(xs_[k], ys_[k], b_.result(k));
    b_.count = 0;
  }

 private:
  void shade(const Bounds3* lanes = nullptr) {
    cullLights(b_, ctx_, lights_, lanes);
    shadeBatch(b_, ctx_);
  }

  const ShadingContext& ctx_;
  Buffer& out_;
  ShadeBatch b_;
  int xs_[ShadeBatch::kMax], ys_[ShadeBatch::kMax];
  std::vector<uint32_t> lights_;
};

}  // namespace tandem
