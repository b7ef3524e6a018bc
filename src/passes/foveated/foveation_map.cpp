#include "passes/foveated/foveation_map.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "rt/sampler.h"

namespace tandem {

void FoveationDesc::validate(const std::string& where) const {
  if (!(r0 >= 0)) throw InputError(where, "r0", "must be >= 0");
  if (!(r1 >= r0)) throw InputError(where, "r1", "must be >= r0 (the middle ring's outer radius)");
  if (!(p >= 0 && p <= 1)) throw InputError(where, "p", "must be in [0, 1]");
  if (outerP >= 0 && !(outerP <= 1)) throw InputError(where, "outer_p", "must be in [0, 1]");
  static const char* names[3] = {"spp_inner", "spp_middle", "spp_outer"};
  for (int i = 0; i < 3; ++i)
    if (spp[i] < 1 || spp[i] > 1024) throw InputError(where, names[i], "must be in [1, 1024]");
}

bool FoveationDesc::operator==(const FoveationDesc& o) const {
  return r0 == o.r0 && r1 == o.r1 && p == o.p && outerP == o.outerP && spp[0] == o.spp[0] &&
         spp[1] == o.spp[1] && spp[2] == o.spp[2] && gaze.x == o.gaze.x && gaze.y == o.gaze.y &&
         seed == o.seed && rotation == o.rotation && full == o.full;
}

int64_t FoveationMap::totalSamples() const {
  return layers[0].samples() + layers[1].samples() + layers[2].samples();
}

double discAreaInRect(Vec2 c, double r, int w, int h) {
  if (r <= 0) return 0;
  if (c.x - r >= 0 && c.x + r <= w && c.y - r >= 0 && c.y + r <= h) return M_PI * r * r;
  // Column integral of the clipped chord; the chord's square-root ends are integrated finely.
  const double xa = std::max(0.0, double(c.x) - r), xb = std::min(double(w), double(c.x) + r);
  if (xb <= xa) return 0;
  const int steps = std::max(1, int(std::ceil((xb - xa) * 256)));
  const double dx = (xb - xa) / steps;
  double area = 0;
  for (int i = 0; i < steps; ++i) {
    const double x = xa + (i + 0.5) * dx - c.x;
    const double s = std::sqrt(std::max(0.0, r * r - x * x));
    area += std::max(0.0, std::min(double(h), c.y + s) - std::max(0.0, c.y - s)) * dx;
  }
  return area;
}

namespace {

// A uniform number per (seed, pixel) for the selection toss: the same map for a seed.
float toss(uint64_t seed, uint32_t pixel) {
  uint64_t z = seed * 0x9e3779b97f4a7c15ull + pixel + 0x632be59bd9b4e019ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return float(z >> 40) * (1.0f / 16777216.0f);
}

// Pixel i's toss turned by `rotation` golden-ratio steps: for a fixed pixel the turned tosses
// are the golden-ratio sequence from its toss, which falls below q on a share q of the frames
// with the gaps between them as even as a sequence allows.
float turnedToss(uint64_t seed, uint32_t pixel, uint32_t rotation) {
  const float u = toss(seed, pixel);
  if (rotation == 0) return u;
  const double t = double(u) + double(rotation) * 0.61803398874989484820;
  return float(t - std::floor(t));
}

// The k pixels nearest g (by squared distance of their centres, ties by index). Only pixels
// within `margin` of radius r are ranked: the k-th distance of a disc's worth of pixels lies a
// small fraction of a pixel from r; when it does not (a disc clipped oddly), all pixels are.
std::vector<uint32_t> nearestPixels(int width, int height, Vec2 g, double r, size_t k) {
  using Key = std::pair<double, uint32_t>;
  const size_t n = size_t(width) * size_t(height);
  std::vector<uint32_t> out;
  if (k == 0) return out;
  auto d2 = [&](int x, int y) {
    const double dx = x + 0.5 - double(g.x), dy = y + 0.5 - double(g.y);
    return dx * dx + dy * dy;
  };
  auto rankAll = [&] {
    std::vector<Key> all(n);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const uint32_t i = uint32_t(y) * uint32_t(width) + uint32_t(x);
        all[i] = {d2(x, y), i};
      }
    const size_t kk = std::min(k, n);
    if (kk < n) std::nth_element(all.begin(), all.begin() + ptrdiff_t(kk), all.end());
    std::vector<uint32_t> r(kk);
    for (size_t i = 0; i < kk; ++i) r[i] = all[i].second;
    return r;
  };
  if (k >= n) return rankAll();
  const double margin = 2.0, lo = std::max(r - margin, 0.0), hi = r + margin;
  std::vector<Key> band;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double d = d2(x, y);
      const uint32_t i = uint32_t(y) * uint32_t(width) + uint32_t(x);
      if (d < lo * lo)
        out.push_back(i);
      else if (d < hi * hi)
        band.push_back({d, i});
    }
  if (out.size() > k || out.size() + band.size() < k) return rankAll();
  const size_t need = k - out.size();
  std::nth_element(band.begin(), band.begin() + ptrdiff_t(need), band.end());
  for (size_t i = 0; i < need; ++i) out.push_back(band[i].second);
  return out;
}

}  // namespace

FoveationMap computeFoveation(int width, int height, const FoveationDesc& desc) {
  FoveationMap m;
  m.width = width;
  m.height = height;
  const size_t n = size_t(width) * size_t(height);
  m.layer.assign(n, desc.full ? 0 : 2);
  const Vec2 g(desc.gaze.x * float(width), desc.gaze.y * float(height));
  if (!desc.full) {
    // The first round(area) pixels by distance from the gaze (ties by pixel order) are inside.
    const size_t k0 = size_t(std::llround(discAreaInRect(g, desc.r0, width, height)));
    const size_t k1 = std::max(k0, size_t(std::llround(discAreaInRect(g, desc.r1, width, height))));
    const std::vector<uint32_t> inner = nearestPixels(width, height, g, desc.r0, k0);
    const std::vector<uint32_t> disc = nearestPixels(width, height, g, desc.r1, k1);
    for (uint32_t i : disc) m.layer[i] = 1;
    for (uint32_t i : inner) m.layer[i] = 0;
    m.layers[0].radius = desc.r0;
    m.layers[1].radius = desc.r1;
  }
  reselectFoveation(m, desc);
  return m;
}

void reselectFoveation(FoveationMap& m, const FoveationDesc& desc) {
  const int width = m.width, height = m.height;
  const size_t n = size_t(width) * size_t(height);
  m.spp.resize(n);
  const Vec2 g(desc.gaze.x * float(width), desc.gaze.y * float(height));
  const float outer = desc.outerProbability(), span = std::max(desc.r1 - desc.r0, 1e-6f);
  // Rows in parallel (a rotating selection is tossed again every frame), each counting its
  // pixels per layer; the listed ones are then gathered in row order.
  using Counts = std::vector<std::array<int64_t, 3>>;
  Counts area = Counts(size_t(height)), listed = Counts(size_t(height));
  parallelRows(height, [&](int y) {
    std::array<int64_t, 3>&a = area[size_t(y)], &l = listed[size_t(y)];
    a = l = {0, 0, 0};
    for (int x = 0; x < width; ++x) {
      const size_t i = size_t(y) * size_t(width) + size_t(x);
      const int L = m.layer[i];
      float prob = 1.0f;
      if (L == 1) {  // (a full map's pixels are all inner)
        const Vec2 r = Vec2(x + 0.5f, y + 0.5f) - g;
        const float d = std::sqrt(r.x * r.x + r.y * r.y);
        const float t = std::clamp((d - desc.r0) / span, 0.0f, 1.0f);
        prob = 1.0f - (1.0f - desc.p) * t;  // linear decay from 1 at r0 to p at r1
      } else if (L == 2) {
        prob = outer;
      }
      ++a[size_t(L)];
      const bool in = prob >= 1.0f || turnedToss(desc.seed, uint32_t(i), desc.rotation) < prob;
      m.spp[i] = in ? uint16_t(desc.spp[L]) : uint16_t(0);
      l[size_t(L)] += in;
    }
  });
  std::vector<size_t> first(size_t(height) + 1, 0);
  for (int L = 0; L < 3; ++L) m.layers[L].area = m.layers[L].listed = 0;
  for (int y = 0; y < height; ++y) {
    const std::array<int64_t, 3>&a = area[size_t(y)], &l = listed[size_t(y)];
    for (int L = 0; L < 3; ++L) {
      m.layers[L].area += a[size_t(L)];
      m.layers[L].listed += l[size_t(L)];
    }
    first[size_t(y) + 1] = first[size_t(y)] + size_t(l[0] + l[1] + l[2]);
  }
  for (int L = 0; L < 3; ++L) m.layers[L].spp = desc.spp[L];
  m.coords.resize(first.back());
  parallelRows(height, [&](int y) {
    size_t k = first[size_t(y)];
    for (int x = 0; x < width; ++x) {
      const size_t i = size_t(y) * size_t(width) + size_t(x);
      if (m.spp[i]) m.coords[k++] = uint32_t(i);
    }
  });
}

}  // namespace tandem
