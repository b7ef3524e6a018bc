#include "passes/pt_reference.h"

#include "core/hash.h"
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
          {"max_depth", ParamType::Int, 16, 1, 1024, "maximum path length in bounces", {}},
          {"progress", ParamType::Bool, 1, 0, 1, "progress bar on a terminal's stderr", {}},
          {"accumulate",
           ParamType::Bool,
           0,
           0,
           1,
           "keep converging over frames while nothing changes (viewer)",
           {}},
          {"frame_spp", ParamType::Int, 4, 1, 1024, "accumulate: samples added per frame", {}}};
}

void PTReferencePass::execute(FrameContext& ctx) {
  const auto t0 = Clock::now();
  RayTracer& rt = ctx.rayTracer();  // (re)builds the BVH: reported apart from the sampling
  ctx.passParts.push_back({"bvh", msSince(t0), 0});
  ReferenceSettings settings;
  settings.spp = int(param("spp"));
  settings.timeLimitS = param("time_limit");
  settings.path.maxDepth = int(param("max_depth"));
  settings.progress = param("progress") != 0;
  settings.seed = ctx.seed * 0x9E3779B97F4A7C15ull + uint64_t(ctx.frameIndex);
  SampleCluster single;
  SampleCluster& cluster = ctx.cluster ? *ctx.cluster : single;
  SampleSums fresh;
  SampleSums& sums = param("accumulate") != 0 ? sums_ : fresh;
  if (param("accumulate") != 0) {
    // Samples continue by index, so the frame number must not change the sequence.
    settings.seed = ctx.seed * 0x9E3779B97F4A7C15ull;
    // Everything the samples depend on; any change starts the accumulation over.
    Hasher h;
    h.pod(ctx.camera.viewProj)
        .pod(ctx.shutterCamera.viewProj)
        .pod(ctx.camera.desc.apertureDiameter);
    h.pod(ctx.camera.desc.focusDistance).pod(ctx.camera.desc.apertureBlades);
    // Scene time matters only through moved geometry (geometryVersion) and the shutter length.
    h.pod(ctx.frame.geometryVersion).pod(ctx.frame.shutterClose - ctx.frame.time);
    h.pod(ctx.width).pod(ctx.height).pod(settings.seed).pod(settings.path.maxDepth);
    h.pod(ctx.scene);
    if (h.value() != stateKey_ || sums.width != ctx.width || sums.height != ctx.height) {
      sums.reset(ctx.width, ctx.height);
      stateKey_ = h.value();
    }
    settings.spp = std::min(settings.spp, sums.samples + int(param("frame_spp")));
    settings.timeLimitS = 0;
    settings.progress = false;
  }
  ReferenceResult r =
      renderReference(rt, *ctx.scene, ctx.camera, ctx.shutterCamera, settings, cluster, sums);
  Buffer& hdr = ctx.output(bufferName("hdr"), 3);
  Buffer& variance = ctx.output(bufferName("variance"), 1);
  sums.resolve(hdr, &variance);
  ctx.samplesPerPixel = r.spp;
  ctx.passRays += double(r.rays);
  ctx.passParts.push_back({"sampling", r.seconds * 1e3, double(r.rays)});
}

}  // namespace tandem
