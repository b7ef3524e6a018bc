#include "passes/baselines/pt_reference.h"

#include "pipeline/frame_context.h"
#include "rt/reference_render.h"

namespace tandem {

const ParamTable<PTReferenceSettings>& PTReferencePass::tableFor() const {
  using S = PTReferenceSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::spp,
               {.name = "spp", .min = 1, .max = 1 << 20, .doc = "target samples per pixel"})
          .add(&S::timeLimit, {.name = "time_limit",
                               .min = 0,
                               .max = 1e7,
                               .doc = "seconds; > 0 stops at the last batch that fits"})
          .add(&S::maxDepth, {.name = "max_depth",
                              .min = 1,
                              .max = 1024,
                              .doc = "maximum path length in bounces",
                              .invalidatesHistory = true})
          .add(&S::progress, {.name = "progress", .doc = "progress bar on a terminal's stderr"})
          .add(&S::accumulate,
               {.name = "accumulate",
                .doc = "keep converging over frames while nothing changes (viewer)"})
          .add(&S::frameSpp, {.name = "frame_spp",
                              .min = 1,
                              .max = 1024,
                              .doc = "accumulate: samples added per frame"})
          .add(&S::integrator,
               {.name = "integrator",
                .doc = "path: path tracing (global illumination); whitted: distributed ray tracing "
                       "of the hybrids' shading (shadows, mirrors, glass; the same light transport "
                       "as rt-only); diffuse-gi: the foveated pipelines' path tracer, converged",
                .choices = {"path", "whitted", "diffuse-gi"},
                .invalidatesHistory = true})
          .add(&S::whittedDepth,
               {.name = "whitted_depth",
                .min = 1,
                .max = 64,
                .doc = "whitted: recursion depth of secondary rays (rt_whitted's max_depth)",
                .invalidatesHistory = true});
  return table;
}

std::vector<CounterDesc> PTReferencePass::counters() const {
  return {
      {PTReferenceCounters::spp, "samples per pixel accumulated so far"},
  };
}

void PTReferencePass::execute(FrameContext& ctx) {
  const auto t0 = Clock::now();
  RayTracer& rt = ctx.rayTracer();  // (re)builds the BVH: reported apart from the sampling
  ctx.passParts.push_back({"bvh", msSince(t0), 0});
  const PTReferenceSettings& s = settings();
  ReferenceSettings ref;
  ref.spp = s.spp;
  ref.timeLimitS = s.timeLimit;
  ref.path.maxDepth = s.maxDepth;
  ref.integrator = s.integrator;
  ref.whitted.maxDepth = s.whittedDepth;
  ref.progress = s.progress;
  ref.seed = ctx.seed * 0x9E3779B97F4A7C15ull + uint64_t(ctx.frameIndex);
  SampleCluster single;
  SampleCluster& cluster = cluster_ ? *cluster_ : single;
  const bool accumulate = s.accumulate;
  if (accumulate) {
    // Samples continue by index, so the frame number must not change the sequence.
    ref.seed = ctx.seed * 0x9E3779B97F4A7C15ull;
    // History resets (scene, size, pipeline, lens, max_depth) clear sums_; a moved camera or
    // moved geometry starts over too (scene time matters only through moved geometry).
    if (ctx.anyCameraMoved() || ctx.frame.geometryVersion != geometryVersion_) sums_.clear();
    geometryVersion_ = ctx.frame.geometryVersion;
    ref.timeLimitS = 0;
    ref.progress = false;
  } else {
    sums_.clear();
  }
  sums_.resize(ctx.views.size());
  Buffer& hdr = ctx.output(*this, Slots::hdr);
  Buffer& variance = ctx.output(*this, Slots::variance);
  int spp = 0;
  double seconds = 0;
  for (size_t i = 0; i < ctx.views.size(); ++i) {
    const View& v = ctx.views[i];
    SampleSums& sums = sums_[i];
    if (sums.width != v.width() || sums.height != v.height()) sums.reset(v.width(), v.height());
    ReferenceSettings eye = ref;
    eye.seed += uint64_t(i) * 0xD1B54A32D192ED03ull;  // eyes get independent samples
    if (accumulate) eye.spp = std::min(ref.spp, sums.samples + s.frameSpp);
    ReferenceResult r =
        renderReference(rt, *ctx.scene, v.camera, v.shutterCamera, eye, cluster, sums);
    spp = i == 0 ? r.spp : std::min(spp, r.spp);
    seconds += r.seconds;
    ctx.passRays += double(r.rays);
    if (ctx.views.size() == 1) {
      sums.resolve(hdr, &variance);
    } else {
      Buffer h(v.width(), v.height(), 3), var(v.width(), v.height(), 1);
      sums.resolve(h, &var);
      for (int y = 0; y < v.height(); ++y)
        for (int x = 0; x < v.width(); ++x) {
          hdr.setRgb(x + v.x, y + v.y, h.rgb(x, y));
          variance.at(x + v.x, y + v.y)[0] = var.at(x, y)[0];
        }
    }
  }
  ctx.report(*this, PTReferenceCounters::spp, spp);
  ctx.passParts.push_back({"sampling", seconds * 1e3, ctx.passRays});
}

}  // namespace tandem
