#include "passes/foveated/atrous.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>

namespace tandem {

void AtrousImage::resize(int w, int h) {
  width = w;
  height = h;
  const size_t n = size_t(w) * size_t(h);
  for (int k = 0; k < 3; ++k) {
    c[k].assign(n, 0.0f);
    this->n[k].assign(n, 0.0f);
    x[k].assign(n, 0.0f);
  }
  positionScale.assign(n, 1.0f);
  sampled.assign(n, 0.0f);
  known.assign(n, 0.0f);
  var.assign(n, 0.0f);
  colorScale.assign(n, 0.0f);
  for (int k = 0; k < 3; ++k) g[k].clear();  // allocated by the variance-guided weight only
  gvar.clear();
}

float sampledMeanLuminance(const AtrousImage& img) {
  double sum = 0;
  size_t count = 0;
  for (size_t i = 0; i < img.sampled.size(); ++i)
    if (img.sampled[i] > 0) {
      sum += planeLuminance(img, i);
      ++count;
    }
  return std::max(float(count ? sum / double(count) : 0.0), 1e-4f);
}

namespace {

constexpr float kSpline[5] = {1.0f / 16, 1.0f / 4, 3.0f / 8, 1.0f / 4, 1.0f / 16};

// exp(-e) for e >= 0 without a library call (relative error < 2e-5), so the tap loop vectorises.
inline float expNeg(float e) {
  float x = -e * 1.44269504f;  // log2 of the result
  x = x < -126.0f ? -126.0f : x;
  const int xi = int(x);  // toward zero: f in (-1, 0]
  const float f = (x - float(xi)) * 0.69314718f;
  const float p =
      1.0f + f * (1.0f + f * (0.5f + f * (1.0f / 6 +
                                          f * (1.0f / 24 + f * (1.0f / 120 + f * (1.0f / 720))))));
  return p * std::bit_cast<float>((xi + 127) << 23);
}

// The planes a tap reads: colour (summed), the colour guide (compared; the colour itself unless
// a separate guide is kept), normal, position, mask and variance.
struct TapPlanes {
  const float *c0, *c1, *c2, *g0, *g1, *g2, *n0, *n1, *n2, *x0, *x1, *x2, *b, *v;
};

// Eq. 4.1 x 4.2: the weight of neighbour j for centre i (the kernel's, the edge-stopping terms
// and the mask); `colorScale` is the centre's 1 / (colour σ)², 0 where it has no estimate to
// compare with.
__attribute__((always_inline)) inline float tapWeight(
    const float* g0, const float* g1, const float* g2, const float* n0, const float* n1,
    const float* n2, const float* x0, const float* x1, const float* x2, const float* b, int i,
    ptrdiff_t j, float kernel, float colorScale, float invNormal, float scale) {
  const float dr = g0[j] - g0[i], dg = g1[j] - g1[i], db = g2[j] - g2[i];
  const float dnx = n0[j] - n0[i], dny = n1[j] - n1[i], dnz = n2[j] - n2[i];
  const float dxx = x0[j] - x0[i], dxy = x1[j] - x1[i], dxz = x2[j] - x2[i];
  const float e = (dr * dr + dg * dg + db * db) * colorScale +
                  (dnx * dnx + dny * dny + dnz * dnz) * invNormal +
                  (dxx * dxx + dxy * dxy + dxz * dxz) * scale;
  return kernel * b[j] * expNeg(e);
}

// Accumulates one tap row segment: centres u = [0, count) of the span (pointers at the span's
// first centre), neighbours at offset `offset` from each centre.
__attribute__((target_clones("avx2", "default"))) void accumulateTap(
    const TapPlanes& p, ptrdiff_t offset, int count, float kernel, float invNormal,
    const float* __restrict scale, const float* __restrict colorScale, float* __restrict sr,
    float* __restrict sg, float* __restrict sb, float* __restrict sw, float* __restrict sv) {
  const float* __restrict c0 = p.c0, * __restrict c1 = p.c1, * __restrict c2 = p.c2;
  const float* __restrict g0 = p.g0, * __restrict g1 = p.g1, * __restrict g2 = p.g2;
  const float* __restrict n0 = p.n0, * __restrict n1 = p.n1, * __restrict n2 = p.n2;
  const float* __restrict x0 = p.x0, * __restrict x1 = p.x1, * __restrict x2 = p.x2;
  const float* __restrict b = p.b, * __restrict v = p.v;
  for (int i = 0; i < count; ++i) {
    const ptrdiff_t j = i + offset;
    const float w = tapWeight(g0, g1, g2, n0, n1, n2, x0, x1, x2, b, i, j, kernel, colorScale[i],
                              invNormal, scale[i]);
    sr[i] += w * c0[j];
    sg[i] += w * c1[j];
    sb[i] += w * c2[j];
    sw[i] += w;
    sv[i] += w * w * v[j];
  }
}

// All the taps of centres [0, count) whose neighbours all lie inside the view, eight centres at
// a time with their sums in registers (the same sums in the same order as accumulateTap).
__attribute__((target_clones("avx2", "default"))) void accumulateTaps(
    const TapPlanes& p, const ptrdiff_t* offsets, const float* kernels, int taps, int count,
    float invNormal, const float* __restrict scale, const float* __restrict colorScale,
    float* __restrict sr, float* __restrict sg, float* __restrict sb, float* __restrict sw,
    float* __restrict sv) {
  const float* __restrict c0 = p.c0, * __restrict c1 = p.c1, * __restrict c2 = p.c2;
  const float* __restrict g0 = p.g0, * __restrict g1 = p.g1, * __restrict g2 = p.g2;
  const float* __restrict n0 = p.n0, * __restrict n1 = p.n1, * __restrict n2 = p.n2;
  const float* __restrict x0 = p.x0, * __restrict x1 = p.x1, * __restrict x2 = p.x2;
  const float* __restrict b = p.b, * __restrict v = p.v;
  int i0 = 0;
  for (; i0 + 8 <= count; i0 += 8) {
    float ar[8] = {}, ag[8] = {}, ab[8] = {}, aw[8] = {}, av[8] = {};
    for (int t = 0; t < taps; ++t) {
      const ptrdiff_t o = offsets[t];
      const float kernel = kernels[t];
      for (int l = 0; l < 8; ++l) {
        const int i = i0 + l;
        const ptrdiff_t j = i + o;
        const float w = tapWeight(g0, g1, g2, n0, n1, n2, x0, x1, x2, b, i, j, kernel,
                                  colorScale[i], invNormal, scale[i]);
        ar[l] += w * c0[j];
        ag[l] += w * c1[j];
        ab[l] += w * c2[j];
        aw[l] += w;
        av[l] += w * w * v[j];
      }
    }
    for (int l = 0; l < 8; ++l) {
      sr[i0 + l] += ar[l];
      sg[i0 + l] += ag[l];
      sb[i0 + l] += ab[l];
      sw[i0 + l] += aw[l];
      sv[i0 + l] += av[l];
    }
  }
  if (i0 < count) {
    const TapPlanes rest{p.c0 + i0, p.c1 + i0, p.c2 + i0, p.g0 + i0, p.g1 + i0,
                         p.g2 + i0, p.n0 + i0, p.n1 + i0, p.n2 + i0, p.x0 + i0,
                         p.x1 + i0, p.x2 + i0, p.b + i0,  p.v + i0};
    for (int t = 0; t < taps; ++t)
      accumulateTap(rest, offsets[t], count - i0, kernels[t], invNormal, scale + i0,
                    colorScale + i0, sr + i0, sg + i0, sb + i0, sw + i0, sv + i0);
  }
}

}  // namespace

namespace {

// The region's spans cut into pieces of at most kPiece pixels, ordered by column strip, then
// row: consecutive pieces (one worker's range) read the same few hundred columns of the 5 tap
// rows, which stay in cache even at a 16-pixel step on a 3664-pixel-wide dual image.
constexpr int kPiece = 128;
std::vector<AtrousSpan> cacheOrderedPieces(const AtrousRegion& region) {
  std::vector<AtrousSpan> pieces;
  for (const AtrousSpan& sp : region.spans)
    for (int x = sp.x0; x < sp.x1; x += kPiece) {
      AtrousSpan p = sp;
      p.x0 = x;
      p.x1 = std::min(sp.x1, x + kPiece);
      pieces.push_back(p);
    }
  std::stable_sort(pieces.begin(), pieces.end(), [](const AtrousSpan& a, const AtrousSpan& b) {
    return a.x0 / kPiece != b.x0 / kPiece ? a.x0 / kPiece < b.x0 / kPiece : a.y < b.y;
  });
  return pieces;
}

}  // namespace

void atrousLevel(AtrousImage& img, const AtrousRegion& region, int step, int iteration,
                 float meanLuminance, const AtrousWeights& w) {
  // Each piece's results go to its own slice of `out` (5 floats per pixel: r, g, b, weight and
  // the variance sum) and are written back after every piece is done, so every tap reads the
  // values before this level.
  const std::vector<AtrousSpan> pieces = cacheOrderedPieces(region);
  std::vector<size_t> first(pieces.size() + 1, 0);
  for (size_t s = 0; s < pieces.size(); ++s)
    first[s + 1] = first[s] + size_t(pieces[s].x1 - pieces[s].x0);
  // Kept in the image between levels and frames: a fresh vector of this size (140 MB at quest2)
  // would be mapped and page-faulted in, zero-filled, every level.
  std::vector<float>& out = img.scratch;
  out.resize(first.back() * 5);
  std::fill(out.begin(), out.end(), 0.0f);
  const float sc = w.sigmaColor * meanLuminance;
  const float invColor = 1.0f / std::max(sc * sc * std::ldexp(1.0f, -iteration), 1e-20f);
  const float invNormal = 1.0f / std::max(w.sigmaNormal * w.sigmaNormal, 1e-20f);
  // The centres' colour σ: Dammertz's (relative to the mean, halved each level) or, guided by
  // variance, σ_v standard deviations of the difference of two estimates (2 var per luminance,
  // x3 for the RGB distance), floored so a pixel whose samples agreed keeps a little tolerance.
  const float floorVar = 1e-6f * meanLuminance * meanLuminance;
  const std::vector<float>* guide = w.varianceGuided ? img.g : img.c;
  const float sv2 = 6.0f * w.sigmaVariance * w.sigmaVariance;
  tbb::parallel_for(size_t(0), pieces.size(), [&](size_t s) {
    const AtrousSpan& sp = pieces[s];
    const size_t u0 = img.index(sp.x0, sp.y);
    for (int i = 0; i < sp.x1 - sp.x0; ++i) {
      const size_t u = u0 + size_t(i);
      img.colorScale[u] = img.known[u] <= 0.0f ? 0.0f
                          : w.varianceGuided   ? 1.0f / (sv2 * std::max(img.gvar[u], floorVar))
                                               : invColor;
    }
  });
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pieces.size(), 16), [&](const auto& range) {
    for (size_t s = range.begin(); s != range.end(); ++s) {
      const AtrousSpan& sp = pieces[s];
      const int count = sp.x1 - sp.x0;
      float* acc = &out[first[s] * 5];
      float *sr = acc, *sg = acc + count, *sb = acc + 2 * count, *sw = acc + 3 * count,
            *sv = acc + 4 * count;
      const size_t u0 = img.index(sp.x0, sp.y);
      if (sp.x0 - 2 * step >= sp.vx0 && sp.x1 + 2 * step <= sp.vx1) {
        // Every tap of every centre is inside the view in x: all rows' taps at once.
        ptrdiff_t offsets[25];
        float kernels[25];
        int taps = 0;
        for (int ty = 0; ty < 5; ++ty) {
          const int dy = (ty - 2) * step;
          if (sp.y + dy < sp.vy0 || sp.y + dy >= sp.vy1) continue;
          for (int tx = 0; tx < 5; ++tx) {
            offsets[taps] = ptrdiff_t(dy) * img.width + (tx - 2) * step;
            kernels[taps++] = kSpline[ty] * kSpline[tx];
          }
        }
        const TapPlanes p{&img.c[0][u0],    &img.c[1][u0], &img.c[2][u0], &guide[0][u0],
                          &guide[1][u0],    &guide[2][u0], &img.n[0][u0], &img.n[1][u0],
                          &img.n[2][u0],    &img.x[0][u0], &img.x[1][u0], &img.x[2][u0],
                          &img.sampled[u0], &img.var[u0]};
        accumulateTaps(p, offsets, kernels, taps, count, invNormal, &img.positionScale[u0],
                       &img.colorScale[u0], sr, sg, sb, sw, sv);
        continue;
      }
      for (int ty = 0; ty < 5; ++ty) {
        const int dy = (ty - 2) * step;
        if (sp.y + dy < sp.vy0 || sp.y + dy >= sp.vy1) continue;
        for (int tx = 0; tx < 5; ++tx) {
          const int dx = (tx - 2) * step;
          // Centres whose neighbour lies inside the view: [xa, xb).
          const int xa = std::max(sp.x0, sp.vx0 - dx), xb = std::min(sp.x1, sp.vx1 - dx);
          if (xb <= xa) continue;
          const size_t u = u0 + size_t(xa - sp.x0);
          const TapPlanes p{&img.c[0][u], &img.c[1][u], &img.c[2][u],    &guide[0][u], &guide[1][u],
                            &guide[2][u], &img.n[0][u], &img.n[1][u],    &img.n[2][u], &img.x[0][u],
                            &img.x[1][u], &img.x[2][u], &img.sampled[u], &img.var[u]};
          const int o = xa - sp.x0;
          accumulateTap(p, ptrdiff_t(dy) * img.width + dx, xb - xa, kSpline[ty] * kSpline[tx],
                        invNormal, &img.positionScale[u], &img.colorScale[u], sr + o, sg + o,
                        sb + o, sw + o, sv + o);
        }
      }
    }
  });
  tbb::parallel_for(size_t(0), pieces.size(), [&](size_t s) {
    const AtrousSpan& sp = pieces[s];
    const int count = sp.x1 - sp.x0;
    const float* acc = &out[first[s] * 5];
    const size_t u0 = img.index(sp.x0, sp.y);
    for (int i = 0; i < count; ++i) {
      const size_t u = u0 + size_t(i);
      float wsum = acc[3 * count + i];
      float sr = acc[i], sg = acc[count + i], sb = acc[2 * count + i], sv = acc[4 * count + i];
      if (w.varianceGuided && img.sampled[u] <= 0 && img.known[u] > 0) {
        // An unsampled pixel's own estimate (from sampled pixels only) is its centre tap:
        // otherwise taps its colour weight all but rejected would, normalised, take it over.
        const float k = kSpline[2] * kSpline[2];
        sr += k * img.c[0][u];
        sg += k * img.c[1][u];
        sb += k * img.c[2][u];
        sv += k * k * img.var[u];
        wsum += k;
      }
      // No usable tap (or weights so small their reciprocal would overflow): keep the value.
      if (!(wsum > 1e-30f)) continue;
      const float inv = 1.0f / wsum;
      img.c[0][u] = sr * inv;
      img.c[1][u] = sg * inv;
      img.c[2][u] = sb * inv;
      // The weighted mean's variance (the taps' noise taken as independent).
      img.var[u] = sv * inv * inv;
      img.known[u] = 1.0f;
      if (w.varianceGuided) {  // from now on the pixel's filtered estimate is its guide
        for (int k = 0; k < 3; ++k) img.g[k][u] = img.c[k][u];
        img.gvar[u] = img.var[u];
      }
    }
  });
}

std::vector<std::pair<int, int>> nonHomogeneousAtrous(AtrousImage& img,
                                                      const std::vector<AtrousRegion>& regions,
                                                      const AtrousWeights& w, float mean) {
  std::vector<std::pair<int, int>> log;
  for (size_t r = 0; r < regions.size(); ++r) {
    if (regions[r].spans.empty()) continue;
    for (int level = regions[r].levels - 1, k = 0; level >= 0; --level, ++k) {
      atrousLevel(img, regions[r], 1 << level, k, mean, w);
      log.push_back({int(r), 1 << level});
    }
  }
  return log;
}

}  // namespace tandem
