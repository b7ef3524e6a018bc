#include "core/image_filters.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace tandem {

namespace {

inline int clampi(int v, int lo, int hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

// One 1-D pass along rows (horizontal) or columns (vertical) with clamp-to-edge.
Buffer convolve1d(const Buffer& in, const std::vector<float>& k, bool horizontal) {
  Buffer out(in.width, in.height, in.channels, 0.0f, in.kind);
  const int r = int(k.size()) / 2, C = in.channels, W = in.width, H = in.height;
  parallelRange(
      size_t(H),
      [&](size_t y0, size_t y1) {
        for (size_t y = y0; y < y1; ++y) {
          float* o = &out.data[y * size_t(W) * C];
          for (int t = -r; t <= r; ++t) {
            const float w = k[size_t(t + r)];
            if (w == 0.0f) continue;
            if (horizontal) {
              const float* row = &in.data[y * size_t(W) * C];
              // Interior: one contiguous multiply-add over the row (vectorised).
              const int xa = std::min(W, std::max(0, -t)), xb = std::max(xa, std::min(W, W - t));
              for (int i = xa * C; i < xb * C; ++i) o[i] += w * row[i + t * C];
              for (int x = 0; x < xa; ++x)
                for (int c = 0; c < C; ++c)
                  o[x * C + c] += w * row[clampi(x + t, 0, W - 1) * C + c];
              for (int x = xb; x < W; ++x)
                for (int c = 0; c < C; ++c)
                  o[x * C + c] += w * row[clampi(x + t, 0, W - 1) * C + c];
            } else {
              const float* row = &in.data[size_t(clampi(int(y) + t, 0, H - 1)) * W * C];
              for (int i = 0; i < W * C; ++i) o[i] += w * row[i];
            }
          }
        }
      },
      8);
  return out;
}

}  // namespace

Buffer separableFilter(const Buffer& in, const std::vector<float>& kx,
                       const std::vector<float>& ky) {
  return convolve1d(convolve1d(in, kx, true), ky, false);
}

std::vector<float> gaussianKernel(float sigma) {
  if (!(sigma > 0.0f)) return {};
  const int r = int(std::ceil(3.0f * sigma));
  std::vector<float> k(size_t(2 * r + 1));
  float sum = 0.0f;
  for (int i = -r; i <= r; ++i)
    sum += k[size_t(i + r)] = std::exp(-0.5f * float(i * i) / (sigma * sigma));
  for (float& w : k) w /= sum;
  return k;
}

Buffer gaussianBlur(const Buffer& in, float sigma) {
  if (!(sigma > 0.0f)) return in;
  const std::vector<float> k = gaussianKernel(sigma);
  return separableFilter(in, k, k);
}

Buffer sobel5x5(const Buffer& in, int channel) {
  Buffer one(in.width, in.height, 1, 0.0f, in.kind);
  for (size_t i = 0; i < one.pixelCount(); ++i) one.data[i] = in.data[i * in.channels + channel];
  const std::vector<float> smooth = {1, 4, 6, 4, 1}, derive = {-1, -2, 0, 2, 1};
  // convolve1d correlates (out[x] = sum w[t] in[x + t]), so `derive` reads as d/dx.
  const Buffer gx = separableFilter(one, derive, smooth), gy = separableFilter(one, smooth, derive);
  Buffer out(in.width, in.height, 2, 0.0f, BufferKind::Motion);
  for (size_t i = 0; i < one.pixelCount(); ++i) {
    out.data[2 * i] = gx.data[i];
    out.data[2 * i + 1] = gy.data[i];
  }
  return out;
}

namespace {

// The median of nine values by a fixed network of 19 compare-exchanges (min/max, no branches):
// the exchange network of Smith 1996 ("Implementing median filters in XC4000E FPGAs"), which
// Tan et al. 2022 §3.1.3 uses on the GPU.
inline float median9(float p[9]) {
  auto sort = [](float& a, float& b) {
    const float lo = std::min(a, b), hi = std::max(a, b);
    a = lo;
    b = hi;
  };
  sort(p[1], p[2]), sort(p[4], p[5]), sort(p[7], p[8]);
  sort(p[0], p[1]), sort(p[3], p[4]), sort(p[6], p[7]);
  sort(p[1], p[2]), sort(p[4], p[5]), sort(p[7], p[8]);
  sort(p[0], p[3]), sort(p[5], p[8]), sort(p[4], p[7]);
  sort(p[3], p[6]), sort(p[1], p[4]), sort(p[2], p[5]);
  sort(p[4], p[7]), sort(p[4], p[2]), sort(p[6], p[4]);
  sort(p[4], p[2]);
  return p[4];
}

}  // namespace

Buffer median3x3(const Buffer& in) {
  Buffer out(in.width, in.height, in.channels, 0.0f, in.kind);
  const int W = in.width, H = in.height, C = in.channels;
  parallelRange(
      size_t(H),
      [&](size_t y0, size_t y1) {
        float v[9];
        for (int y = int(y0); y < int(y1); ++y) {
          const float* rows[3];
          for (int dy = -1; dy <= 1; ++dy) rows[dy + 1] = in.at(0, clampi(y + dy, 0, H - 1));
          for (int x = 0; x < W; ++x) {
            const int xs[3] = {clampi(x - 1, 0, W - 1) * C, x * C, clampi(x + 1, 0, W - 1) * C};
            for (int c = 0; c < C; ++c) {
              int n = 0;
              for (int dy = 0; dy < 3; ++dy)
                for (int dx = 0; dx < 3; ++dx) v[n++] = rows[dy][xs[dx] + c];
              out.at(x, y)[c] = median9(v);
            }
          }
        }
      },
      4);
  return out;
}

Buffer downsampleBox(const Buffer& in) {
  const int W = (in.width + 1) / 2, H = (in.height + 1) / 2, C = in.channels;
  Buffer out(W, H, C, 0.0f, in.kind);
  parallelRange(
      size_t(H),
      [&](size_t y0, size_t y1) {
        for (int y = int(y0); y < int(y1); ++y)
          for (int x = 0; x < W; ++x) {
            const int xa = 2 * x, ya = 2 * y, xb = std::min(xa + 1, in.width - 1),
                      yb = std::min(ya + 1, in.height - 1);
            const float n = float((xb - xa + 1) * (yb - ya + 1));
            for (int c = 0; c < C; ++c) {
              float s = in.at(xa, ya)[c];
              if (xb != xa) s += in.at(xb, ya)[c];
              if (yb != ya) s += in.at(xa, yb)[c];
              if (xb != xa && yb != ya) s += in.at(xb, yb)[c];
              out.at(x, y)[c] = s / n;
            }
          }
      },
      8);
  return out;
}

void sampleBilinear(const Buffer& b, float x, float y, float* out) {
  const float fx = x - 0.5f, fy = y - 0.5f;
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const float tx = fx - float(x0), ty = fy - float(y0);
  const int xa = clampi(x0, 0, b.width - 1), xb = clampi(x0 + 1, 0, b.width - 1);
  const int ya = clampi(y0, 0, b.height - 1), yb = clampi(y0 + 1, 0, b.height - 1);
  const float *p00 = b.at(xa, ya), *p10 = b.at(xb, ya), *p01 = b.at(xa, yb), *p11 = b.at(xb, yb);
  for (int c = 0; c < b.channels; ++c)
    out[c] = (p00[c] * (1 - tx) + p10[c] * tx) * (1 - ty) + (p01[c] * (1 - tx) + p11[c] * tx) * ty;
}

void sampleCatmullRom(const Buffer& b, float x, float y, float* out) {
  const float fx = x - 0.5f, fy = y - 0.5f;
  const int x1 = int(std::floor(fx)), y1 = int(std::floor(fy));
  float wx[4], wy[4];
  catmullRomWeights(fx - float(x1), wx);
  catmullRomWeights(fy - float(y1), wy);
  for (int c = 0; c < b.channels; ++c) out[c] = 0.0f;
  if (x1 >= 1 && y1 >= 1 && x1 + 2 < b.width && y1 + 2 < b.height) {
    // Inside: four rows of four contiguous texels, no clamping.
    const int C = b.channels;
    for (int j = 0; j < 4; ++j) {
      const float* row = b.at(x1 - 1, y1 - 1 + j);
      for (int i = 0; i < 4; ++i) {
        const float w = wx[i] * wy[j];
        for (int c = 0; c < C; ++c) out[c] += w * row[i * C + c];
      }
    }
    return;
  }
  for (int j = 0; j < 4; ++j) {
    const int yy = clampi(y1 - 1 + j, 0, b.height - 1);
    for (int i = 0; i < 4; ++i) {
      const float w = wx[i] * wy[j];
      const float* p = b.at(clampi(x1 - 1 + i, 0, b.width - 1), yy);
      for (int c = 0; c < b.channels; ++c) out[c] += w * p[c];
    }
  }
}

Buffer resizeBilinear(const Buffer& in, int width, int height) {
  Buffer out(width, height, in.channels, 0.0f, in.kind);
  const float sx = float(in.width) / float(width), sy = float(in.height) / float(height);
  parallelRange(
      size_t(height),
      [&](size_t y0, size_t y1) {
        for (int y = int(y0); y < int(y1); ++y)
          for (int x = 0; x < width; ++x)
            sampleBilinear(in, (float(x) + 0.5f) * sx, (float(y) + 0.5f) * sy, out.at(x, y));
      },
      8);
  return out;
}

Buffer upsampleDepthAware(const Buffer& low, const Buffer& lowDepth, const Buffer& highDepth,
                          float depthScale) {
  const int W = highDepth.width, H = highDepth.height, C = low.channels;
  Buffer out(W, H, C, 0.0f, low.kind);
  const float sx = float(low.width) / float(W), sy = float(low.height) / float(H);
  parallelRange(
      size_t(H),
      [&](size_t y0, size_t y1) {
        for (int y = int(y0); y < int(y1); ++y)
          for (int x = 0; x < W; ++x) {
            const float fx = (float(x) + 0.5f) * sx - 0.5f, fy = (float(y) + 0.5f) * sy - 0.5f;
            const int bx = int(std::floor(fx)), by = int(std::floor(fy));
            const float tx = fx - float(bx), ty = fy - float(by);
            const float d = highDepth.at(x, y)[0];
            float wsum = 0.0f;
            float* o = out.at(x, y);
            for (int j = 0; j < 2; ++j)
              for (int i = 0; i < 2; ++i) {
                const int lx = clampi(bx + i, 0, low.width - 1),
                          ly = clampi(by + j, 0, low.height - 1);
                const float wb = (i ? tx : 1 - tx) * (j ? ty : 1 - ty);
                const float dd = std::abs(lowDepth.at(lx, ly)[0] - d) * depthScale;
                const float w = wb / (1e-4f + dd * dd) + 1e-12f;
                wsum += w;
                const float* p = low.at(lx, ly);
                for (int c = 0; c < C; ++c) o[c] += w * p[c];
              }
            for (int c = 0; c < C; ++c) o[c] /= wsum;
          }
      },
      8);
  return out;
}

std::vector<Buffer> mipChain(const Buffer& in) {
  std::vector<Buffer> levels{in};
  while (levels.back().width > 1 || levels.back().height > 1)
    levels.push_back(downsampleBox(levels.back()));
  return levels;
}

}  // namespace tandem
