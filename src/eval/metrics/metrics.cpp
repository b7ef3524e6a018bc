#include "eval/metrics/metrics.h"

#include "core/interrupt.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace tandem {

namespace {
void checkShapes(const Buffer& a, const Buffer& b) {
  TANDEM_ASSERT(a.width == b.width && a.height == b.height && a.channels == b.channels);
}
}  // namespace

double rmse(const Buffer& a, const Buffer& b) {
  checkShapes(a, b);
  double sum = 0;
  for (size_t i = 0; i < a.data.size(); ++i) {
    double d = double(a.data[i]) - b.data[i];
    sum += d * d;
  }
  return a.data.empty() ? 0.0 : std::sqrt(sum / double(a.data.size()));
}

double psnr(const Buffer& a, const Buffer& b, double peak) {
  double e = rmse(a, b);
  if (e == 0) return std::numeric_limits<double>::infinity();
  return 20.0 * std::log10(peak / e);
}

double ssim(const Buffer& a, const Buffer& b, Buffer* map) {
  checkShapes(a, b);
  const int W = a.width, H = a.height, C = a.channels, R = 5;
  const double c1 = (0.01 * 0.01), c2 = (0.03 * 0.03);
  double g[2 * R + 1];
  for (int k = -R; k <= R; ++k) g[k + R] = std::exp(-(k * k) / (2.0 * 1.5 * 1.5));
  if (map) *map = Buffer(W, H, 1);
  // Separable Gaussian moments (mu_a, mu_b, E[a^2], E[b^2], E[ab]) per channel: rows filtered
  // into a ring of the 2R+1 rows the column filter reads, so memory is O(W), not O(W*H).
  constexpr int kRing = 2 * R + 1;
  std::vector<double> ring(size_t(W) * kRing * 5);
  auto filterRow = [&](int c, int y) {
    double* out = &ring[size_t(y % kRing) * W * 5];
    for (int x = 0; x < W; ++x) {
      double acc[5] = {0, 0, 0, 0, 0}, wsum = 0;
      for (int k = -R; k <= R; ++k) {
        const int xx = x + k;
        if (xx < 0 || xx >= W) continue;
        const size_t i = size_t(y) * W + xx;
        const double u = a.data[i * C + c], v = b.data[i * C + c];
        const double s[5] = {u, v, u * u, v * v, u * v};
        const double w = g[k + R];
        for (int m = 0; m < 5; ++m) acc[m] += w * s[m];
        wsum += w;
      }
      for (int m = 0; m < 5; ++m) out[x * 5 + m] = acc[m] / wsum;
    }
  };
  double total = 0;
  for (int c = 0; c < C; ++c) {
    for (int y = 0; y < std::min(R, H); ++y) filterRow(c, y);
    for (int y = 0; y < H; ++y) {
      if (y % 64 == 0) pollInterrupt();  // a Python caller's Ctrl-C
      if (y + R < H) filterRow(c, y + R);
      for (int x = 0; x < W; ++x) {
        double acc[5] = {0, 0, 0, 0, 0}, wsum = 0;
        for (int k = -R; k <= R; ++k) {
          const int yy = y + k;
          if (yy < 0 || yy >= H) continue;
          const double* s = &ring[(size_t(yy % kRing) * W + x) * 5];
          const double w = g[k + R];
          for (int m = 0; m < 5; ++m) acc[m] += w * s[m];
          wsum += w;
        }
        const double mx = acc[0] / wsum, my = acc[1] / wsum;
        const double vx = std::max(acc[2] / wsum - mx * mx, 0.0),
                     vy = std::max(acc[3] / wsum - my * my, 0.0);
        const double cov = acc[4] / wsum - mx * my;
        const double s =
            ((2 * mx * my + c1) * (2 * cov + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
        total += s;
        if (map) map->data[size_t(y) * W + x] += float(s / C);
      }
    }
  }
  return total / (double(W) * H * C);
}

void requireFinitePixels(const Buffer& img, const std::string& source, const std::string& field) {
  const size_t c = size_t(std::max(img.channels, 1));
  size_t bad = 0;
  for (size_t p = 0; p < img.data.size(); p += c) {
    bool finite = true;
    for (size_t k = 0; k < c; ++k) finite &= std::isfinite(img.data[p + k]);
    bad += !finite;
  }
  if (bad > 0)
    throw InputError(source, field,
                     std::to_string(bad) + " of " + std::to_string(img.pixelCount()) +
                         " pixels are not finite (NaN or Inf)");
}

ImageMetrics compareImages(const Buffer& a, const Buffer& b, Buffer* ssimMap) {
  return {rmse(a, b), psnr(a, b), ssim(a, b, ssimMap)};
}

Buffer heatMap(const Buffer& scalar, float maxValue) {
  Buffer out(scalar.width, scalar.height, 3);
  for (size_t i = 0; i < scalar.pixelCount(); ++i) {
    float t =
        maxValue > 0 ? std::clamp(scalar.data[i * scalar.channels] / maxValue, 0.0f, 1.0f) : 0.0f;
    // Piecewise-linear ramp: blue (0) -> green (1/3) -> yellow (2/3) -> red (1).
    Vec3 c = t < 1.0f / 3   ? lerp({0, 0, 1}, {0, 1, 0}, t * 3)
             : t < 2.0f / 3 ? lerp({0, 1, 0}, {1, 1, 0}, t * 3 - 1)
                            : lerp({1, 1, 0}, {1, 0, 0}, t * 3 - 2);
    out.setRgb(int(i % scalar.width), int(i / scalar.width), c);
  }
  return out;
}

}  // namespace tandem
