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
  // Separable Gaussian moments: mu_a, mu_b, E[a^2], E[b^2], E[ab] per channel.
  std::vector<double> src(size_t(W) * H * 5), tmp(size_t(W) * H * 5), mom(size_t(W) * H * 5);
  double total = 0;
  for (int c = 0; c < C; ++c) {
    for (size_t i = 0; i < size_t(W) * H; ++i) {
      double x = a.data[i * C + c], y = b.data[i * C + c];
      double* s = &src[i * 5];
      s[0] = x;
      s[1] = y;
      s[2] = x * x;
      s[3] = y * y;
      s[4] = x * y;
    }
    for (int pass = 0; pass < 2; ++pass) {
      const std::vector<double>& in = pass == 0 ? src : tmp;
      std::vector<double>& out = pass == 0 ? tmp : mom;
      for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
          if (x == 0 && y % 64 == 0) pollInterrupt();  // a Python caller's Ctrl-C
          double acc[5] = {0, 0, 0, 0, 0}, wsum = 0;
          for (int k = -R; k <= R; ++k) {
            int xx = pass == 0 ? x + k : x, yy = pass == 0 ? y : y + k;
            if (xx < 0 || yy < 0 || xx >= W || yy >= H) continue;
            const double* s = &in[(size_t(yy) * W + xx) * 5];
            double w = g[k + R];
            for (int m = 0; m < 5; ++m) acc[m] += w * s[m];
            wsum += w;
          }
          double* o = &out[(size_t(y) * W + x) * 5];
          for (int m = 0; m < 5; ++m) o[m] = acc[m] / wsum;
        }
    }
    for (size_t i = 0; i < size_t(W) * H; ++i) {
      const double* m = &mom[i * 5];
      double mx = m[0], my = m[1];
      double vx = std::max(m[2] - mx * mx, 0.0), vy = std::max(m[3] - my * my, 0.0);
      double cov = m[4] - mx * my;
      double s =
          ((2 * mx * my + c1) * (2 * cov + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
      total += s;
      if (map) map->data[i] += float(s / C);
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
