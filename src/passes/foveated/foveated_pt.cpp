#include "passes/foveated/foveated_pt.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <cstdio>

#include "core/profiler.h"
#include "passes/foveated/foveation.h"
#include "passes/foveated/primary_surface.h"
#include "pipeline/frame_context.h"
#include "rt/diffuse_gi.h"
#include "scene/scene.h"

namespace tandem {

std::vector<BufferSlot> FoveatedPTPass::inputs() const {
  std::vector<BufferSlot> slots = PrimarySurfaces::slots();
  slots.push_back(CoordChannels::slot());
  return slots;
}

const ParamTable<FoveatedPTSettings>& FoveatedPTPass::tableFor() const {
  using S = FoveatedPTSettings;
  static const ParamTable<S> table = ParamTable<S>().add(
      &S::lightSelection, {.name = "light_selection",
                           .doc = "uniform: any light alike (the thesis); grid: by estimated "
                                  "irradiance where the path is",
                           .choices = {"uniform", "grid"}});
  return table;
}

std::vector<CounterDesc> FoveatedPTPass::counters() const {
  return {
      {FoveatedPTCounters::lightGridBuilt, "1 on a frame that built the light grid"},
      {FoveatedPTCounters::lightGridProbeRays, "rays the light grid's build traced"},
      {FoveatedPTCounters::samples, "path samples traced"},
  };
}

const LightGrid* FoveatedPTPass::prepare(FrameContext& ctx, const ShadingContext& shading) {
  if (warnedScene_ != ctx.scene) {
    warnedScene_ = ctx.scene;
    if (const std::string note = DiffuseGI::blackMaterialsNote(*ctx.scene); !note.empty())
      std::fprintf(stderr, "tandem: warning: %s\n", note.c_str());
  }
  if (settings().lightSelection != FoveatedPTSettings::LightSelection::Grid) return nullptr;
  const uint64_t key = lightSetKey(shading.lights, DiffuseGI::lightsSampled(*ctx.scene));
  if (!grid_ || key != gridKey_ || gridScene_ != ctx.scene) {
    const auto t0 = Clock::now();
    grid_ =
        std::make_unique<LightGrid>(DiffuseGI::buildGrid(*ctx.scene, shading, &ctx.rayTracer()));
    gridKey_ = key;
    gridScene_ = ctx.scene;
    ctx.report(*this, FoveatedPTCounters::lightGridBuilt, 1);
    ctx.report(*this, FoveatedPTCounters::lightGridProbeRays, double(grid_->probeRays()));
    ctx.passParts.push_back({"light_grid", msSince(t0), 0});
  }
  return grid_.get();
}

void FoveatedPTPass::execute(FrameContext& ctx) {
  const PrimarySurfaces g = PrimarySurfaces::of(ctx, *this);
  const Buffer& coords = ctx.input(*this, Slots::fovCoords);
  Buffer& out = ctx.output(*this, Slots::ptNoisy);
  Buffer& variance = ctx.output(*this, Slots::ptVariance);
  out.fill(0.0f);
  variance.fill(0.0f);
  const RayTracer& rt = ctx.rayTracer();
  const ShadingContext shading = ShadingContext::from(*ctx.scene);
  const LightGrid* grid = prepare(ctx, shading);
  const DiffuseGI gi(rt, *ctx.scene, shading, grid);
  const uint64_t seed = ctx.frameSeed();
  const size_t listed = size_t(coords.width) * (coords.height > 0 ? 1 : 0);
  const size_t eyes = ctx.views.size();
  std::atomic<uint64_t> rays{0}, samples{0};
  // One dispatch over both eyes: entry k is coordinate k % listed of eye k / listed.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, listed * eyes, 64), [&](const auto& range) {
    uint64_t localRays = 0, localSamples = 0;
    for (size_t k = range.begin(); k != range.end(); ++k) {
      const View& v = ctx.views[k / listed];
      const float* c = coords.at(int(k % listed), 0);
      using K = CoordChannels;
      const int ex = int(c[K::kX]), ey = int(c[K::kY]), spp = int(c[K::kSpp]);
      if (ex >= v.width() || ey >= v.height()) continue;
      const int x = ex + v.x, y = ey + v.y;
      Vec3 sum(0.0f);
      double lum2 = 0;  // the samples' squared luminances
      if (g.sky(x, y)) {
        Vec3 o, d;
        v.jitteredCamera.generateRay(ex + 0.5f, ey + 0.5f, o, d);
        sum = ctx.scene->skyRadiance(d) * float(spp);
      } else {
        const SurfaceSample s = g.at(x, y);
        const Vec3 wo = PrimarySurfaces::towardsViewer(v, s.position);
        const uint64_t pixel = uint64_t(y) * uint64_t(ctx.width) + uint64_t(x);
        for (int i = 0; i < spp; ++i) {
          SobolSampler rng(seed, pixel, uint32_t(i));
          Vec3 L = gi.radiance(s, wo, rng, 0.0f, localRays);
          if (std::isfinite(L.x) && std::isfinite(L.y) && std::isfinite(L.z)) {
            sum += L;
            lum2 += double(luminance(L)) * double(luminance(L));
          }
        }
      }
      localSamples += uint64_t(spp);
      const float n = float(std::max(spp, 1));
      out.setRgb(x, y, sum / n);
      // The variance of the mean's luminance from the samples' spread; unknown (-1) from one.
      const double mean = double(luminance(sum)) / n;
      variance.at(x, y)[0] =
          spp >= 2 ? float(std::max(lum2 - n * mean * mean, 0.0) / ((n - 1.0) * n)) : -1.0f;
    }
    rays += localRays;
    samples += localSamples;
  });
  ctx.passRays += double(rays.load());
  ctx.report(*this, FoveatedPTCounters::samples, double(samples.load()));
}

}  // namespace tandem
