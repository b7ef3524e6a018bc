#include "passes/foveated/foveation.h"

#include "core/profiler.h"
#include "pipeline/frame_context.h"
#include "scene/scene.h"

namespace tandem {

std::vector<ParamDesc> FoveationPass::params() const {
  using T = ParamType;
  return {
      {"mode",
       T::Enum,
       0,
       0,
       1,
       "foveated: three layers; full: every pixel (Base)",
       {"foveated", "full"}},
      {"r0", T::Float, 144, 0, 16384, "inner (fovea) radius in pixels", {}},
      {"r1", T::Float, 288, 0, 16384, "middle ring's outer radius in pixels (>= r0)", {}},
      {"p",
       T::Float,
       0.5,
       0,
       1,
       "middle ring's probability at r1 (falls linearly from 1 at r0)",
       {}},
      {"outer_p",
       T::Float,
       -1,
       -1,
       1,
       "outer layer's probability; -1: p (the thesis' 1 - p at p = 0.5)",
       {}},
      {"spp_inner", T::Int, 4, 1, 1024, "samples per listed pixel, inner layer", {}},
      {"spp_middle", T::Int, 3, 1, 1024, "samples per listed pixel, middle ring", {}},
      {"spp_outer", T::Int, 2, 1, 1024, "samples per listed pixel, outer layer", {}},
      {"gaze",
       T::Enum,
       0,
       0,
       1,
       "trace: the scene's gazeTrace at the frame time when it has one; fixed: gaze_x, gaze_y",
       {"trace", "fixed"}},
      {"gaze_x", T::Float, 0.5, 0, 1, "gaze point, fraction of the eye's width", {}},
      {"gaze_y", T::Float, 0.5, 0, 1, "gaze point, fraction of the eye's height", {}},
      {"scale_radii",
       T::Bool,
       1,
       0,
       1,
       "radii are for 1080 rows: scale them to the eye's height",
       {}},
      {"seed", T::Int, 0, 0, 1e9, "seed of the selection toss", {}},
  };
}

FoveationDesc FoveationPass::desc(int width, int height) const {
  (void)width;
  FoveationDesc d;
  d.full = param("mode") == 1;
  const float k = param("scale_radii") != 0 ? float(height) / 1080.0f : 1.0f;
  d.r0 = float(param("r0")) * k;
  d.r1 = float(param("r1")) * k;
  d.p = float(param("p"));
  d.outerP = float(param("outer_p"));
  d.spp[0] = int(param("spp_inner"));
  d.spp[1] = int(param("spp_middle"));
  d.spp[2] = int(param("spp_outer"));
  d.gaze = Vec2(float(param("gaze_x")), float(param("gaze_y")));
  d.seed = uint64_t(param("seed"));
  return d;
}

void FoveationPass::execute(FrameContext& ctx) {
  const View& eye = ctx.views.front();
  FoveationDesc d = desc(eye.width(), eye.height());
  // A moving gaze: the distribution is rebuilt only on the frames where the point moves.
  if (param("gaze") == 0 && ctx.scene && !ctx.scene->gazeTrace.empty())
    d.gaze = sampleGazeTrace(ctx.scene->gazeTrace, ctx.frame.time);
  d.validate("pass foveation");
  const bool rebuild =
      !valid_ || !(d == built_) || map_.width != eye.width() || map_.height != eye.height();
  if (rebuild) {
    const auto t0 = Clock::now();
    map_ = computeFoveation(eye.width(), eye.height(), d);
    built_ = d;
    valid_ = true;
    ctx.passParts.push_back({"distribution", msSince(t0), 0});
  }
  ctx.counters["foveation/recomputed"] = rebuild ? 1 : 0;
  ctx.counters["foveation/listed"] = double(map_.coords.size() * ctx.views.size());
  ctx.counters["foveation/samples"] = double(map_.totalSamples() * int64_t(ctx.views.size()));
  Buffer& coords = ctx.output(*this, "fov_coords", int(map_.coords.size()), 1);
  Buffer& mask = ctx.output(*this, "fov_mask");
  Buffer& layer = ctx.output(*this, "fov_layer");
  if (!rebuild && written_ == mask.data.data() && !ctx.historyReset) return;
  for (size_t i = 0; i < map_.coords.size(); ++i) {
    const uint32_t px = map_.coords[i];
    float* c = coords.at(int(i), 0);
    c[0] = float(px % uint32_t(map_.width));
    c[1] = float(px / uint32_t(map_.width));
    c[2] = float(map_.spp[px]);
  }
  mask.fill(0.0f);
  layer.fill(2.0f);
  for (const View& v : ctx.views)
    for (int y = 0; y < std::min(v.height(), map_.height); ++y)
      for (int x = 0; x < std::min(v.width(), map_.width); ++x) {
        const size_t i = size_t(y) * size_t(map_.width) + size_t(x);
        mask.at(x + v.x, y + v.y)[0] = map_.spp[i] ? 1.0f : 0.0f;
        layer.at(x + v.x, y + v.y)[0] = float(map_.layer[i]);
      }
  written_ = mask.data.data();
}

}  // namespace tandem
