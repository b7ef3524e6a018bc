#include "passes/foveated/nh_denoise.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "core/profiler.h"
#include "passes/foveated/atrous.h"
#include "passes/foveated/demodulation.h"
#include "pipeline/frame_context.h"
#include "shading/gbuffer_layout.h"

namespace tandem {

namespace {

struct RegionNoise {
  double variance = 0;  // of a listed pixel's luminance about its listed 3x3 neighbours' mean
  double density = 0;   // listed share of the region's pixels
};

// The noise of a region's estimate, measured on this frame: at a few samples per pixel the
// difference between a pixel and the mean of its listed neighbours on the same surface (normals
// within 25°) is noise, not signal.
RegionNoise measureNoise(const AtrousImage& img, const AtrousRegion& region) {
  // Fixed blocks of spans in parallel, their sums added in order: the same total every run.
  constexpr size_t kBlock = 64;
  struct Sums {
    double sum = 0, listed = 0, total = 0, used = 0;
  };
  std::vector<Sums> blocks((region.spans.size() + kBlock - 1) / kBlock);
  const auto lum = [&](size_t i) { return planeLuminance(img, i); };
  parallelBlocks(region.spans.size(), kBlock, [&](size_t b, size_t e) {
    Sums& t = blocks[b / kBlock];
    for (size_t k = b; k < e; ++k) {
      const AtrousSpan& sp = region.spans[k];
      for (int x = sp.x0; x < sp.x1; ++x) {
        ++t.total;
        const size_t u = img.index(x, sp.y);
        if (img.sampled[u] <= 0) continue;
        ++t.listed;
        double m = 0;
        int n = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = sp.y + dy;
            if ((dx == 0 && dy == 0) || nx < sp.vx0 || nx >= sp.vx1 || ny < sp.vy0 || ny >= sp.vy1)
              continue;
            const size_t j = img.index(nx, ny);
            const float cosN =
                img.n[0][u] * img.n[0][j] + img.n[1][u] * img.n[1][j] + img.n[2][u] * img.n[2][j];
            if (img.sampled[j] <= 0 || cosN < 0.9f) continue;
            m += lum(j);
            ++n;
          }
        if (n == 0) continue;
        const double d = lum(u) - m / n;
        t.sum += d * d;
        ++t.used;
      }
    }
  });
  Sums all;
  for (const Sums& t : blocks) {
    all.sum += t.sum, all.listed += t.listed, all.total += t.total, all.used += t.used;
  }
  return {all.used > 0 ? all.sum / all.used : 0.0, all.total > 0 ? all.listed / all.total : 0.0};
}

}  // namespace

// Whether pixels i and j show the same surface for the variance and guide estimates: normals
// within ~25°, or both without a normal (the sky, which the G-buffer leaves at 0).
static bool sameSurface(const AtrousImage& img, size_t i, size_t j) {
  const float cosN =
      img.n[0][i] * img.n[0][j] + img.n[1][i] * img.n[1][j] + img.n[2][i] * img.n[2][j];
  const auto none = [&](size_t k) {
    return img.n[0][k] * img.n[0][k] + img.n[1][k] * img.n[1][k] + img.n[2][k] * img.n[2][k] <
           0.25f;
  };
  return i == j || cosN >= 0.9f || (none(i) && none(j));
}

// Calls fn(j, dx, dy) for each sampled pixel j of view v within r pixels of (x, y) (the square),
// in row order.
template <class Fn>
void forSampledNeighbours(const AtrousImage& img, const View& v, int x, int y, int r, Fn&& fn) {
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx) {
      const int nx = x + dx, ny = y + dy;
      if (nx < v.x || nx >= v.x + v.width() || ny < v.y || ny >= v.y + v.height()) continue;
      const size_t j = img.index(nx, ny);
      if (img.sampled[j] > 0) fn(j, dx, dy);
    }
}

// SVGF's variance prefilter, and its spatial estimate where samples are few: each sampled
// pixel's variance becomes the mean over the sampled pixels of its 3 x 3 neighbourhood (in its
// view) that measured one or, where that is 0, the variance of the luminances of the sampled
// pixels of its surface (normals within ~25°) in its 5 x 5 neighbourhood (at least 4 of them).
// Two samples that agree (often both 0 where light is rare) measure no variance at all; a
// pixel whose neighbours measured none either would reject every neighbour and stay a dark
// speckle. The spatial estimate is only the fallback: across an edge it measures the edge.
// A pixel with neither takes the mean of all.
static void prefilterVariance(AtrousImage& img, const std::vector<View>& views) {
  double total = 0;
  size_t count = 0;
  for (size_t i = 0; i < img.var.size(); ++i)
    if (img.sampled[i] > 0 && img.var[i] >= 0) {
      total += img.var[i];
      ++count;
    }
  const float fallback = count ? float(total / double(count)) : 0.0f;
  std::vector<float> out(img.var.size(), 0.0f);
  for (const View& v : views)
    tbb::parallel_for(v.y, v.y + v.height(), [&](int y) {
      for (int x = v.x; x < v.x + v.width(); ++x) {
        const size_t i = img.index(x, y);
        if (img.sampled[i] <= 0) continue;
        double sum = 0, s1 = 0, s2 = 0;
        int n = 0, m = 0;
        forSampledNeighbours(img, v, x, y, 2, [&](size_t j, int dx, int dy) {
          if (std::abs(dx) <= 1 && std::abs(dy) <= 1 && img.var[j] >= 0) {
            sum += img.var[j];
            ++n;
          }
          if (!sameSurface(img, i, j)) return;
          const double l = planeLuminance(img, j);
          s1 += l;
          s2 += l * l;
          ++m;
        });
        const double spatial = m >= 4 ? std::max(s2 / m - (s1 / m) * (s1 / m), 0.0) : 0.0;
        const double measured = n ? sum / n : double(fallback);
        out[i] = float(measured > 0.0 ? measured : spatial);
      }
    });
  img.var.swap(out);
}

// Before the levels (variance-guided weights only): an unsampled pixel takes, from the sampled
// pixels of the same surface (normals within ~25°) in its 3 x 3, else 5 x 5, neighbourhood, the
// one of median luminance (the side of an edge most of them are on), with its variance, as the
// estimate its colour weight compares taps with. It is still never read as a tap (eq. 4.2);
// without it, its first, widest level would mix both sides of an illumination edge blindly and
// the next levels would keep the mixture.
static void prefillHoles(AtrousImage& img, const std::vector<View>& views) {
  std::vector<int64_t> source(img.var.size(), -1);
  for (const View& v : views)
    tbb::parallel_for(v.y, v.y + v.height(), [&](int y) {
      std::vector<std::pair<float, size_t>> near;
      for (int x = v.x; x < v.x + v.width(); ++x) {
        const size_t i = img.index(x, y);
        if (img.sampled[i] > 0) continue;
        for (int r = 1; r <= 2 && near.empty(); ++r)
          forSampledNeighbours(img, v, x, y, r, [&](size_t j, int, int) {
            if (sameSurface(img, i, j)) near.push_back({float(planeLuminance(img, j)), j});
          });
        if (near.empty()) continue;
        std::nth_element(near.begin(), near.begin() + ptrdiff_t(near.size() / 2), near.end());
        source[i] = int64_t(near[near.size() / 2].second);
        near.clear();
      }
    });
  for (size_t i = 0; i < source.size(); ++i)
    if (source[i] >= 0) {
      const size_t j = size_t(source[i]);
      for (int k = 0; k < 3; ++k) img.c[k][i] = img.c[k][j];
      img.var[i] = img.var[j];
      img.known[i] = 1.0f;
    }
}

// The guide the first level's colour weights compare: a sampled pixel's mean over the sampled
// pixels of its surface (normals within ~25°) in its 3 x 3 neighbourhood, with that mean's
// variance; a prefilled hole's estimate. The widest step comes first (Algorithm 1), so without
// it the weights would compare single pixels of a few samples, too noisy to tell an
// illumination edge from noise.
static void initGuide(AtrousImage& img, const std::vector<View>& views) {
  for (const View& v : views)
    tbb::parallel_for(v.y, v.y + v.height(), [&](int y) {
      for (int x = v.x; x < v.x + v.width(); ++x) {
        const size_t i = img.index(x, y);
        if (img.sampled[i] <= 0) {
          for (int k = 0; k < 3; ++k) img.g[k][i] = img.c[k][i];
          img.gvar[i] = std::max(img.var[i], 0.0f);
          continue;
        }
        double sum[3] = {0, 0, 0}, sumVar = 0;
        int n = 0;
        forSampledNeighbours(img, v, x, y, 1, [&](size_t j, int, int) {
          if (!sameSurface(img, i, j)) return;
          for (int k = 0; k < 3; ++k) sum[k] += img.c[k][j];
          sumVar += img.var[j];
          ++n;
        });
        for (int k = 0; k < 3; ++k) img.g[k][i] = float(sum[k] / n);  // n >= 1: the pixel itself
        img.gvar[i] = float(sumVar / (double(n) * n));
      }
    });
}

// The mean luminance of the sampled pixels' whole illumination when the planes hold it less
// pt_direct's: the planes' colour plus pt_direct's illumination (sampledMeanLuminance's floor).
static float wholeMeanLuminance(const AtrousImage& img, const Buffer& direct,
                                const Demodulation& dm) {
  using Sum = std::pair<double, size_t>;  // luminance sum, sampled pixels
  const Sum total = tbb::parallel_reduce(
      tbb::blocked_range<int>(0, img.height), Sum{0.0, 0},
      [&](const tbb::blocked_range<int>& rows, Sum acc) {
        for (int y = rows.begin(); y != rows.end(); ++y)
          for (int x = 0; x < img.width; ++x) {
            const size_t i = img.index(x, y);
            if (img.sampled[i] <= 0) continue;
            Vec3 c;
            for (int k = 0; k < 3; ++k)
              c[k] = img.c[k][i] + dm.illumination(direct.at(x, y)[k], x, y, k);
            acc.first += luminance(c);
            ++acc.second;
          }
        return acc;
      },
      [](Sum a, const Sum& b) {
        return Sum{a.first + b.first, a.second + b.second};
      });
  return std::max(float(total.second ? total.first / double(total.second) : 0.0), 1e-4f);
}

std::vector<BufferSlot> NHDenoisePass::inputs() const {
  BufferSlot variance{Slots::ptVariance, 1, BufferKind::Variance};
  variance.optional = true;
  BufferSlot direct{Slots::ptDirect, 3, BufferKind::Color};
  direct.optional = true;
  return {{Slots::ptNoisy, 3, BufferKind::Color},
          {Slots::normal, 3, BufferKind::Normal},
          {Slots::position, 3, BufferKind::Position},
          {Slots::depth, 1, BufferKind::Depth},
          gbufferSlot(Slots::diffuse),
          {Slots::emission, 3, BufferKind::Color},
          {Slots::fovMask, 1, BufferKind::Mask},
          {Slots::fovLayer, 1, BufferKind::Id},
          variance,
          direct};
}

const ParamTable<NHDenoiseSettings>& NHDenoisePass::tableFor() const {
  using S = NHDenoiseSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::regions,
               {.name = "regions",
                .doc = "one: whole frame (Base); two: inner + rest (NH2LD); three: NH3LD",
                .choices = {"one", "two", "three"}})
          .add(&S::levelsInner, {.name = "levels_inner",
                                 .min = 0,
                                 .max = 10,
                                 .doc = "M: levels of the inner layer (regions two, three)"})
          .add(&S::levelsMiddle, {.name = "levels_middle",
                                  .min = 0,
                                  .max = 10,
                                  .doc = "N: levels of the middle ring (regions three)"})
          .add(&S::levelsOuter,
               {.name = "levels_outer",
                .min = 0,
                .max = 10,
                .doc = "P: levels of the outer layer (two: middle + outer; one: the frame)"})
          .add(&S::sigmaColor, {.name = "sigma_color",
                                .min = 0.001,
                                .max = 1000,
                                .doc = "colour edge-stopping σ, relative to mean luminance"})
          .add(&S::sigmaNormal,
               {.name = "sigma_normal", .min = 0.001, .max = 10, .doc = "normal edge-stopping σ"})
          .add(&S::sigmaPosition, {.name = "sigma_position",
                                   .min = 0.0001,
                                   .max = 10,
                                   .doc = "position edge-stopping σ, relative to eye distance"})
          .add(&S::demodulate,
               {.name = "demodulate", .doc = "filter illumination (divided by the diffuse albedo)"})
          .add(&S::colorWeight,
               {.name = "color_weight",
                .doc = "mean: σ_c x mean luminance, halved per level (Dammertz); variance: σ_v x "
                       "each pixel's own noise, from pt_variance (beyond the thesis)",
                .choices = {"mean", "variance"}})
          .add(&S::sigmaVariance,
               {.name = "sigma_variance",
                .min = 0.01,
                .max = 100,
                .doc = "variance: colour edge-stopping σ in standard deviations of the pixel's "
                       "estimate"})
          .add(
              &S::levelsFrom,
              {.name = "levels_from",
               .doc = "fixed: the level counts above; variance: per region from its measured noise "
                      "(beyond the thesis)",
               .choices = {"fixed", "variance"}})
          .add(&S::targetVariance,
               {.name = "target_variance",
                .min = 1e-6,
                .max = 10,
                .doc = "variance: the relative noise variance per pixel area each region is "
                       "filtered down to"})
          .add(&S::split,
               {.name = "split",
                .doc = "none: filter the whole estimate (Peres 2022); direct: filter it less "
                       "pt_direct and add pt_direct back (beyond the thesis; needs direct_light)",
                .choices = {"none", "direct"}});
  return table;
}

std::vector<CounterDesc> NHDenoisePass::counters() const {
  std::vector<CounterDesc> c{
      {NHDenoiseCounters::levelsRun, "À-Trous levels run (the deepest region's)"}};
  for (int r = 0; r < NHDenoiseCounters::kMaxRegions; ++r)
    c.push_back(
        {NHDenoiseCounters::levelsRegion(r),
         "levels region " + std::to_string(r) + " chose from its noise (levels_from = variance)"});
  return c;
}

void NHDenoisePass::execute(FrameContext& ctx) {
  const Buffer& noisy = ctx.input(*this, Slots::ptNoisy);
  const Buffer& normal = ctx.input(*this, Slots::normal);
  const Buffer& position = ctx.input(*this, Slots::position);
  const Buffer& depth = ctx.input(*this, Slots::depth);
  const Buffer& diffuse = ctx.input(*this, Slots::diffuse);
  const Buffer& emission = ctx.input(*this, Slots::emission);
  const Buffer& mask = ctx.input(*this, Slots::fovMask);
  const Buffer& layer = ctx.input(*this, Slots::fovLayer);
  Buffer& out = ctx.output(*this, Slots::denoised);
  const int W = ctx.width, H = ctx.height;
  const NHDenoiseSettings& s = settings();
  const bool demodulate = s.demodulate;
  const Buffer* variance = ctx.optionalInput(*this, Slots::ptVariance);
  const Buffer* direct = s.split == NHDenoiseSettings::Split::Direct
                             ? ctx.optionalInput(*this, Slots::ptDirect)
                             : nullptr;
  const AtrousWeights weights{
      s.sigmaColor, s.sigmaNormal, s.sigmaPosition,
      s.colorWeight == NHDenoiseSettings::ColorWeight::Variance && variance != nullptr,
      s.sigmaVariance};
  const Demodulation dm{diffuse, emission, depth, demodulate};
  const auto t0 = Clock::now();
  AtrousImage& img = image_;
  if (img.width != W || img.height != H) img.resize(W, H);
  for (const View& v : ctx.views) {
    const Vec3 eye = v.camera.desc.position;
    tbb::parallel_for(0, v.height(), [&](int row) {
      const int y = row + v.y;
      for (int x = v.x; x < v.x + v.width(); ++x) {
        const size_t i = img.index(x, y);
        const bool sampled = mask.at(x, y)[0] > 0.0f;
        for (int k = 0; k < 3; ++k) {
          // An unsampled pixel's colour is never read: it starts empty, whatever it holds.
          // Split: the part of the estimate pt_direct does not hold, over the albedo.
          img.c[k][i] = !sampled ? 0
                        : direct ? (noisy.at(x, y)[k] - direct->at(x, y)[k]) / dm.albedo(x, y, k)
                                 : dm.illumination(noisy.at(x, y)[k], x, y, k);
          img.n[k][i] = normal.at(x, y)[k];
          img.x[k][i] = position.at(x, y)[k];
        }
        img.sampled[i] = img.known[i] = sampled ? 1.0f : 0.0f;
        // The estimate's variance in the filtered quantity's units (-1: not measured).
        const float a = luminance(Vec3(dm.albedo(x, y, 0), dm.albedo(x, y, 1), dm.albedo(x, y, 2)));
        const float v = variance ? variance->at(x, y)[0] : -1.0f;
        img.var[i] = sampled && v >= 0.0f ? v / (a * a) : -1.0f;
        const float z = depth.at(x, y)[0] > 0
                            ? length(Vec3(img.x[0][i], img.x[1][i], img.x[2][i]) - eye)
                            : 1.0f;
        const float s = weights.sigmaPosition * std::max(z, 1e-6f);
        img.positionScale[i] = 1.0f / (s * s);
      }
    });
  }
  if (weights.varianceGuided) {
    prefilterVariance(img, ctx.views);
    prefillHoles(img, ctx.views);
    if (img.gvar.size() != img.var.size()) {  // the guide planes, only when this weight is used
      for (int k = 0; k < 3; ++k) img.g[k].assign(img.var.size(), 0.0f);
      img.gvar.assign(img.var.size(), 0.0f);
    }
    initGuide(img, ctx.views);
  }
  // Regions as row spans of the layer map, per view (taps never cross into the other eye).
  const int mode = int(s.regions);
  const int levels[3] = {s.levelsInner, s.levelsMiddle, s.levelsOuter};
  const int count = mode + 1;
  std::vector<AtrousRegion> regions(static_cast<size_t>(count));
  auto regionOf = [&](int L) { return mode == 0 ? 0 : mode == 1 ? std::min(L, 1) : L; };
  for (int r = 0; r < count; ++r)
    regions[size_t(r)].levels = mode == 0               ? levels[2]
                                : (mode == 1 && r == 1) ? levels[2]
                                                        : levels[r];
  for (const View& v : ctx.views)
    for (int y = v.y; y < v.y + v.height(); ++y) {
      int x = v.x;
      while (x < v.x + v.width()) {
        const int r = regionOf(std::clamp(int(layer.at(x, y)[0]), 0, 2));
        int end = x + 1;
        while (end < v.x + v.width() && regionOf(std::clamp(int(layer.at(end, y)[0]), 0, 2)) == r)
          ++end;
        regions[size_t(r)].spans.push_back(
            {y, x, end, v.x, v.y, v.x + v.width(), v.y + v.height()});
        x = end;
      }
    }
  // L̄, what the colour σ and the measured noise are relative to: of the whole estimate, also
  // where the filter sees only what pt_direct leaves (whose mean may be near 0).
  const float mean = direct ? wholeMeanLuminance(img, *direct, dm) : sampledMeanLuminance(img);
  if (s.levelsFrom == NHDenoiseSettings::LevelsFrom::Variance) {
    const float target = s.targetVariance;
    for (size_t r = 0; r < regions.size(); ++r) {
      const RegionNoise noise = measureNoise(img, regions[r]);
      // Each level widens the footprint about fourfold: levels = log4 of the noise per pixel
      // area (the variance over the listed share) over the target.
      const double perArea = noise.variance / (double(mean) * mean) / std::max(noise.density, 1e-3);
      regions[r].levels = std::clamp(
          int(std::ceil(std::log(std::max(perArea / target, 1.0)) / std::log(4.0))), 1, 10);
      ctx.report(*this, NHDenoiseCounters::levelsRegion(int(r)), regions[r].levels);
    }
  }
  ctx.passParts.push_back({"setup", msSince(t0), 0});
  const auto t1 = Clock::now();
  steps_ = nonHomogeneousAtrous(img, regions, weights, mean);
  ctx.passParts.push_back({"levels", msSince(t1), 0});
  for (const View& v : ctx.views)
    tbb::parallel_for(0, v.height(), [&](int row) {
      const int y = row + v.y;
      for (int x = v.x; x < v.x + v.width(); ++x) {
        const size_t i = img.index(x, y);
        for (int k = 0; k < 3; ++k)
          // Split: the filtered rest on top of the direct light (light is never negative).
          out.at(x, y)[k] =
              direct ? std::max(img.c[k][i] * dm.albedo(x, y, k) + direct->at(x, y)[k], 0.0f)
                     : dm.colour(img.c[k][i], x, y, k);
      }
    });
  ctx.report(*this, NHDenoiseCounters::levelsRun, double(steps_.size()));
}

}  // namespace tandem
