#include "passes/baselines/pt_reference.h"

#include "pipeline/frame_context.h"
#include "rt/reference_render.h"

namespace tandem {

std::vector<ParamDesc> PTReferencePass::params() const {
  return {{"spp", ParamType::Int, 1024, 1, 1 << 20, "target samples per pixel", {}},
          {"time_limit",
           ParamType::Float,
           0,
           0,
           1e7,
           "seconds; > 0 stops at the last batch that fits",
           {}},
          {"max_depth",
           ParamType::Int,
           16,
           1,
           1024,
           "maximum path length in bounces",
           {},
           /*invalidatesHistory=*/true},
          {"progress", ParamType::Bool, 1, 0, 1, "progress bar on a terminal's stderr", {}},
          {"accumulate",
           ParamType::Bool,
           0,
           0,
           1,
           "keep converging over frames while nothing changes (viewer)",
           {}},
          {"frame_spp", ParamType::Int, 4, 1, 1024, "accumulate: samples added per frame", {}},
          {"integrator",
           ParamType::Enum,
           0,
           0,
           2,
           "path: path tracing (global illumination); whitted: distributed ray tracing of the "
           "hybrids' shading (shadows, mirrors, glass; the same light transport as rt-only); "
           "diffuse-gi: the foveated pipelines' path tracer, converged",
           {"path", "whitted", "diffuse-gi"},
           /*invalidatesHistory=*/true},
          {"whitted_depth",
           ParamType::Int,
           10,
           1,
           64,
           "whitted: recursion depth of secondary rays (rt_whitted's max_depth)",
           {},
           /*invalidatesHistory=*/true}};
}

void PTReferencePass::execute(FrameContext& ctx) {
  const auto t0 = Clock::now();
  RayTracer& rt = ctx.rayTracer();  // (re)builds the BVH: reported apart from the sampling
  ctx.passParts.push_back({"bvh", msSince(t0), 0});
  ReferenceSettings settings;
  settings.spp = int(param("spp"));
  settings.timeLimitS = param("time_limit");
  settings.path.maxDepth = int(param("max_depth"));
  settings.integrator = Integrator(int(param("integrator")));
  settings.whitted.maxDepth = int(param("whitted_depth"));
  settings.progress = param("progress") != 0;
  settings.seed = ctx.seed * 0x9E3779B97F4A7C15ull + uint64_t(ctx.frameIndex);
  SampleCluster single;
  SampleCluster& cluster = ctx.cluster ? *ctx.cluster : single;
  const bool accumulate = param("accumulate") != 0;
  if (accumulate) {
    // Samples continue by index, so the frame number must not change the sequence.
    settings.seed = ctx.seed * 0x9E3779B97F4A7C15ull;
    // History resets (scene, size, pipeline, lens, max_depth) clear sums_; a moved camera or
    // moved geometry starts over too (scene time matters only through moved geometry).
    if (ctx.anyCameraMoved() || ctx.frame.geometryVersion != geometryVersion_) sums_.clear();
    geometryVersion_ = ctx.frame.geometryVersion;
    settings.timeLimitS = 0;
    settings.progress = false;
  } else {
    sums_.clear();
  }
  sums_.resize(ctx.views.size());
  Buffer& hdr = ctx.output(*this, "hdr");
  Buffer& variance = ctx.output(*this, "variance");
  int spp = 0;
  double seconds = 0;
  for (size_t i = 0; i < ctx.views.size(); ++i) {
    const View& v = ctx.views[i];
    SampleSums& sums = sums_[i];
    if (sums.width != v.width() || sums.height != v.height()) sums.reset(v.width(), v.height());
    ReferenceSettings eye = settings;
    eye.seed += uint64_t(i) * 0xD1B54A32D192ED03ull;  // eyes get independent samples
    if (accumulate) eye.spp = std::min(settings.spp, sums.samples + int(param("frame_spp")));
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
  ctx.counters["spp"] = spp;
  ctx.passParts.push_back({"sampling", seconds * 1e3, ctx.passRays});
}

}  // namespace tandem
