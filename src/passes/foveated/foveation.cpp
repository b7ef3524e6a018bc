#include "passes/foveated/foveation.h"

#include "core/parallel.h"
#include "core/profiler.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"
#include "scene/scene.h"

namespace tandem {

const ParamTable<FoveationSettings>& FoveationPass::tableFor() const {
  using S = FoveationSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::mode, {.name = "mode",
                          .doc = "foveated: three layers; full: every pixel (Base)",
                          .choices = {"foveated", "full"}})
          .add(&S::r0,
               {.name = "r0", .min = 0, .max = 16384, .doc = "inner (fovea) radius in pixels"})
          .add(&S::r1, {.name = "r1",
                        .min = 0,
                        .max = 16384,
                        .doc = "middle ring's outer radius in pixels (>= r0)"})
          .add(&S::p, {.name = "p",
                       .min = 0,
                       .max = 1,
                       .doc = "middle ring's probability at r1 (falls linearly from 1 at r0)"})
          .add(&S::outerP,
               {.name = "outer_p",
                .min = -1,
                .max = 1,
                .doc = "outer layer's probability; -1: p (the thesis' 1 - p at p = 0.5)"})
          .add(&S::sppInner, {.name = "spp_inner",
                              .min = 1,
                              .max = 1024,
                              .doc = "samples per listed pixel, inner layer"})
          .add(&S::sppMiddle, {.name = "spp_middle",
                               .min = 1,
                               .max = 1024,
                               .doc = "samples per listed pixel, middle ring"})
          .add(&S::sppOuter, {.name = "spp_outer",
                              .min = 1,
                              .max = 1024,
                              .doc = "samples per listed pixel, outer layer"})
          .add(&S::gaze, {.name = "gaze",
                          .doc = "trace: the scene's gazeTrace at the frame time when it has one; "
                                 "fixed: gaze_x, gaze_y",
                          .choices = {"trace", "fixed"}})
          .add(&S::gazeX, {.name = "gaze_x",
                           .min = 0,
                           .max = 1,
                           .doc = "gaze point, fraction of the eye's width"})
          .add(&S::gazeY, {.name = "gaze_y",
                           .min = 0,
                           .max = 1,
                           .doc = "gaze point, fraction of the eye's height"})
          .add(&S::scaleRadii, {.name = "scale_radii",
                                .doc = "radii are for 1080 rows: scale them to the eye's height"})
          .add(&S::seed,
               {.name = "seed", .min = 0, .max = 1e9, .doc = "seed of the selection toss"})
          .add(&S::rotate,
               {.name = "rotate",
                .doc = "beyond the thesis: the selection toss turns by the golden ratio each "
                       "frame, so a pixel listed with probability q is sampled on a share q of "
                       "the frames (with periphery_accumulation the whole periphery over a few)"});
  return table;
}

FoveationDesc FoveationPass::desc(int width, int height) const {
  (void)width;
  FoveationDesc d;
  const FoveationSettings& s = settings();
  d.full = s.mode == FoveationSettings::Mode::Full;
  const float k = s.scaleRadii ? float(height) / 1080.0f : 1.0f;
  d.r0 = s.r0 * k;
  d.r1 = s.r1 * k;
  d.p = s.p;
  d.outerP = s.outerP;
  d.spp[0] = s.sppInner;
  d.spp[1] = s.sppMiddle;
  d.spp[2] = s.sppOuter;
  d.gaze = Vec2(s.gazeX, s.gazeY);
  d.seed = uint64_t(s.seed);
  return d;
}

std::vector<CounterDesc> FoveationPass::counters() const {
  return {
      {FoveationCounters::recomputed, "1 when the sample distribution was recomputed this frame"},
      {FoveationCounters::listed, "pixels listed for sampling, all views"},
      {FoveationCounters::samples, "samples the distribution asks for, all views"},
  };
}

bool FoveationPass::update(FrameContext& ctx) {
  const View& eye = ctx.views.front();
  FoveationDesc d = desc(eye.width(), eye.height());
  // A moving gaze: the distribution is rebuilt only on the frames where the point moves.
  if (settings().gaze == FoveationSettings::Gaze::Trace && ctx.scene &&
      !ctx.scene->gazeTrace.empty())
    d.gaze = sampleGazeTrace(ctx.scene->gazeTrace, ctx.frame.time);
  if (settings().rotate) d.rotation = uint32_t(ctx.serial);
  d.validate("pass foveation");
  const bool resized = !valid_ || map_.width != eye.width() || map_.height != eye.height();
  FoveationDesc unturned = built_;
  unturned.rotation = d.rotation;
  const bool rebuild = resized || !(d == built_);
  if (rebuild) {
    const auto t0 = Clock::now();
    // Only the toss turned: the layers stand, the pixels are listed again.
    if (!resized && unturned == d)
      reselectFoveation(map_, d);
    else
      map_ = computeFoveation(eye.width(), eye.height(), d);
    built_ = d;
    valid_ = true;
    ctx.passParts.push_back({"distribution", msSince(t0), 0});
  }
  ctx.report(*this, FoveationCounters::recomputed, rebuild ? 1 : 0);
  ctx.report(*this, FoveationCounters::listed, double(map_.coords.size() * ctx.views.size()));
  ctx.report(*this, FoveationCounters::samples,
             double(map_.totalSamples() * int64_t(ctx.views.size())));
  return rebuild;
}

void FoveationPass::write(FrameContext& ctx) {
  Buffer& coords = ctx.output(*this, Slots::fovCoords, int(map_.coords.size()), 1);
  Buffer& mask = ctx.output(*this, Slots::fovMask);
  Buffer& layer = ctx.output(*this, Slots::fovLayer);
  for (size_t i = 0; i < map_.coords.size(); ++i) {
    const uint32_t px = map_.coords[i];
    float* c = coords.at(int(i), 0);
    c[CoordChannels::kX] = float(px % uint32_t(map_.width));
    c[CoordChannels::kY] = float(px / uint32_t(map_.width));
    c[CoordChannels::kSpp] = float(map_.spp[px]);
  }
  mask.fill(0.0f);
  layer.fill(2.0f);
  // (Rows in parallel: a rotating selection writes them every frame.)
  for (const View& v : ctx.views)
    parallelRows(std::min(v.height(), map_.height), [&](int y) {
      for (int x = 0; x < std::min(v.width(), map_.width); ++x) {
        const size_t i = size_t(y) * size_t(map_.width) + size_t(x);
        mask.at(x + v.x, y + v.y)[0] = map_.spp[i] ? 1.0f : 0.0f;
        layer.at(x + v.x, y + v.y)[0] = float(map_.layer[i]);
      }
    });
  written_ = mask.data.data();
}

void FoveationPass::execute(FrameContext& ctx) {
  const bool rebuilt = update(ctx);
  if (!rebuilt && !ctx.historyReset) {  // the buffers kept hold the distribution already
    ctx.output(*this, Slots::fovCoords, int(map_.coords.size()), 1);
    if (written_ == ctx.output(*this, Slots::fovMask).data.data()) {
      ctx.output(*this, Slots::fovLayer);
      return;
    }
  }
  write(ctx);
}

// On the GPU the distribution is still built on the host: it is configuration, not a frame's
// work (the thesis computes it once), and is moved to the device only on the frames that change
// it; the others leave the device's copies as they are and move nothing.
void FoveationPass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  const char* slots[3] = {Slots::fovCoords, Slots::fovMask, Slots::fovLayer};
  bool kept = !update(ctx) && !ctx.historyReset;
  for (const char* slot : slots) kept = kept && gpu.onDevice(bufferName(slot));
  if (kept) {
    ctx.deviceOutput(*this, Slots::fovCoords, int(map_.coords.size()), 1);
    ctx.deviceOutput(*this, Slots::fovMask);
    ctx.deviceOutput(*this, Slots::fovLayer);
    return;
  }
  write(ctx);
  const auto t0 = Clock::now();
  for (const char* slot : slots) gpu.upload(bufferName(slot), ctx.buffers.at(bufferName(slot)));
  ctx.passParts.push_back({"upload", msSince(t0), 0});
}

}  // namespace tandem
