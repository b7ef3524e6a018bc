#include "passes/heuristic/rt_secondary.h"

#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>

#include "core/cycle_clock.h"
#include "gpu/shaders/rt_secondary_spv.h"
#include "gpu/shaders/secondary_args.h"
#include "passes/common/gpu_shadow_maps.h"
#include "passes/common/gpu_whitted.h"
#include "passes/common/lights_in_view.h"
#include "passes/heuristic/ranked_tiles.h"
#include "passes/heuristic/rt_feedback.h"
#include "passes/heuristic/shadow_tile.h"
#include "pipeline/gbuffer_io.h"
#include "pipeline/gpu_frame.h"
#include "pipeline/gpu_gbuffer.h"
#include "pipeline/view_tiles.h"
#include "rt/whitted.h"
#include "shading/shade_batch.h"

namespace tandem {

const ParamTable<RTSecondarySettings>& RTSecondaryPass::tableFor() const {
  using S = RTSecondarySettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .nest(&S::whitted, whittedTable())
          .add(&S::shadowClassLight,
               {.name = "shadow_class_light",
                .min = -1,
                .max = 1 << 20,
                .doc = "the light shadow_class shows (-1: the shares over every light)"})
          .add(&S::outsideMaskShadow,
               {.name = "outside_mask_shadow",
                .min = 0,
                .max = 1,
                .doc = "shadow value outside the mask (Listing 8a: 0; 1 is neutral)"});
  return table;
}

std::vector<BufferSlot> RTSecondaryPass::inputs() const {
  std::vector<BufferSlot> in = gbufferSampleSlots();
  in.push_back(effectSlot(Slots::heuristicMask, BufferKind::Mask));
  in.push_back(rtRequestSlot(true));
  BufferSlot order = effectSlot(Slots::heuristicOrder, BufferKind::List, Extent::any());
  order.optional = true;
  in.push_back(order);
  return in;
}

std::vector<BufferSlot> RTSecondaryPass::outputs() const {
  // shadow_class: each pixel's shares of its light-surface pairs, shown as red, green, blue.
  return {{Slots::shadow, 3},
          {Slots::reflection, 3},
          {Slots::refraction, 3},
          effectSlot(Slots::tracedMask, BufferKind::Mask),
          BufferSlot{Slots::shadowClass}.named({Slots::traced, "lit", "shadowed"}),
          rtStatsSlot(false)};
}

namespace {
using EffectTallies = std::vector<EffectTally>;

// Deadline mode: every worker takes the ranked work items in order and traces them until the
// deadline; the items left stay cleared (traced_mask 0: the fallback covers them). Returns how
// many were left.
template <class Trace>
size_t traceUntilDeadline(const std::vector<RankedTile>& queue, Clock::time_point deadline,
                          Trace&& trace) {
  std::atomic<size_t> next{0}, cut{0};
  const int workers = tbb::this_task_arena::max_concurrency();
  tbb::parallel_for(
      0, workers,
      [&](int) {
        for (size_t i; (i = next.fetch_add(1)) < queue.size();) {
          const RankedTile& t = queue[i];
          if (Clock::now() < deadline)
            trace(*t.view, t.x0, t.y0, t.x1, t.y1, int64_t(t.rank));
          else  // left as cleared: not traced
            cut.fetch_add(1, std::memory_order_relaxed);
        }
      },
      tbb::simple_partitioner());
  return cut.load();
}
}  // namespace

namespace {

// One frame's tracing of masked pixels: the inputs, outputs and settings every tile reads.
struct SecondaryTrace {
  const Scene& scene;
  const ShadingContext& shading;
  RayTracer& rt;
  const Whitted& whitted;
  const GBufferReader& g;
  const Buffer &mask, &ids;
  const Buffer* order;
  Buffer &shadow, &reflection, &refraction, &traced;
  Buffer* classOut;
  int classLight;
  float outsideShadow;
  bool timed;  // ticks counted per object (the ms budget)
  bool tiled;  // shadows go through classifiedShadowTile

  // Listing 8a: 0 in all three outside the mask (`outside_mask_shadow` = 1 keeps the shadow
  // buffer neutral there instead; blend never reads it outside the mask).
  void clearTile(int x0, int y0, int x1, int y1) const {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        shadow.setRgb(x, y, Vec3(outsideShadow));
        reflection.setRgb(x, y, Vec3(0.0f));
        refraction.setRgb(x, y, Vec3(0.0f));
        traced.setRgb(x, y, Vec3(0.0f));
      }
  }
  void traceBlock(const View& v, int bx, int by, int x1, int y1, int64_t rank, EffectTally* tally,
                  LightVisibility8& vis, std::vector<uint8_t>& classes) const;
};

// A 4x2 block's surfaces and the effects each pixel asks for.
struct Block {
  SurfaceSample s[8];
  Vec3 d[8];
  int px[8], py[8], n = 0;
  bool want[8][kEffectCount], hit[8];
  Vec3 shadowRgb[8], reflectionRgb[8], refractionRgb[8];
};

// Listing 8a: the shadow buffer starts at 1 and loses the light each occluder blocks. One
// shading call weighted by (1 - visibility) sums exactly the blocked light.
void shadowBlock(const SecondaryTrace& job, Block& b, LightVisibility8& vis,
                 std::vector<uint8_t>& classes, EffectTally* tally) {
  int lane[8], m = 0;
  SurfaceSample shadowed[8];
  for (int k = 0; k < b.n; ++k)
    if (b.hit[k] && b.want[k][kShadow] && !job.tiled) {
      shadowed[m] = b.s[k];
      lane[m++] = k;
    }
  if (m == 0) return;
  const size_t lights = job.scene.lights.size();
  const uint64_t c0 = job.timed ? cycleNow() : 0;
  int rays[8];
  Vec3 wo[8];
  for (int j = 0; j < m; ++j) wo[j] = -b.d[lane[j]];
  thread_local std::vector<uint32_t> reached;
  job.whitted.lightVisibility8(shadowed, m, vis.data(), rays, wo,
                               job.classOut ? classes.data() : nullptr, &reached);
  if (job.classOut)
    for (int j = 0; j < m; ++j)
      job.classOut->setRgb(b.px[lane[j]], b.py[lane[j]],
                           classShares(classes.data(), lights, 8, j, job.classLight));
  for (uint32_t i : reached)
    for (size_t k = 0; k < 3 * 8; ++k) vis.data()[3 * 8 * i + k] = 1.0f - vis.data()[3 * 8 * i + k];
  ShadeBatch batch;
  batch.count = m;
  for (int j = 0; j < m; ++j) batch.set(j, shadowed[j], -b.d[lane[j]]);
  batch.lights = reached.data();
  batch.lightCount = reached.size();
  shadeBatch(batch, job.shading, vis.data(), 8);
  const uint64_t ticks = job.timed ? cycleNow() - c0 : 0;
  for (int j = 0; j < m; ++j) {
    const SurfaceSample& sj = shadowed[j];
    b.shadowRgb[lane[j]] = shadowFromBlocked(batch, j, job.shading.ambient);
    // What shadows cost this object, in rays and time (the heuristic's ms budget is built from
    // these); the block's time is shared by its lanes.
    EffectTally& t = tally[size_t(sj.object)];
    t.pixels[kShadow] += 1;
    t.rays[kShadow] += uint64_t(rays[j]);
    t.ticks[kShadow] += ticks / uint64_t(m) + (uint64_t(j) < ticks % uint64_t(m) ? 1 : 0);
  }
}

// Reflections and refractions recurse pixel by pixel, each counted to its object.
void reflectRefract(const SecondaryTrace& job, Block& b, int k, EffectTally* tally) {
  EffectTally& t = tally[size_t(b.s[k].object)];
  uint64_t r0 = job.rt.raysOnThisThread(), c0 = job.timed ? cycleNow() : 0;
  auto account = [&](int e) {
    uint64_t r1 = job.rt.raysOnThisThread(), c1 = job.timed ? cycleNow() : 0;
    t.pixels[size_t(e)] += 1;
    t.rays[size_t(e)] += r1 - r0;
    t.ticks[size_t(e)] += c1 - c0;
    r0 = r1;
    c0 = c1;
  };
  if (b.want[k][kReflection] && b.s[k].reflectivity > 0) {
    b.reflectionRgb[k] = job.whitted.primaryReflection(b.s[k], b.d[k]);
    account(kReflection);
  }
  if (b.want[k][kRefraction] && b.s[k].opacity < 1) {
    b.refractionRgb[k] = job.whitted.primaryRefraction(b.s[k], b.d[k]);
    account(kRefraction);
  }
}

void SecondaryTrace::traceBlock(const View& v, int bx, int by, int x1, int y1, int64_t rank,
                                EffectTally* tally, LightVisibility8& vis,
                                std::vector<uint8_t>& classes) const {
  Block b;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) {
      const int x = bx + i, y = by + j, n = b.n;
      if (x >= x1 || y >= y1) continue;
      const float* m = mask.at(x, y);
      for (int e = 0; e < kEffectCount; ++e)
        b.want[n][e] =
            m[e] > 0.5f && (rank < 0 || nodeRank(order, ids.at(x, y)[0], e) == uint32_t(rank));
      b.hit[n] = ((!tiled && b.want[n][0]) || b.want[n][1] || b.want[n][2]) && g.read(x, y, b.s[n]);
      Vec3 origin;
      if (b.hit[n])
        v.jitteredCamera.generateRay(float(x - v.x) + 0.5f, float(y - v.y) + 0.5f, origin, b.d[n]);
      b.px[n] = x;
      b.py[n] = y;
      ++b.n;
    }
  for (int k = 0; k < b.n; ++k) {
    b.shadowRgb[k] = Vec3(b.hit[k] ? 1.0f : outsideShadow);
    b.reflectionRgb[k] = b.refractionRgb[k] = Vec3(0.0f);
  }
  shadowBlock(*this, b, vis, classes, tally);
  for (int k = 0; k < b.n; ++k) {
    if (b.hit[k]) reflectRefract(*this, b, k, tally);
    const int x = b.px[k], y = b.py[k];
    if (rank < 0) {
      shadow.setRgb(x, y, b.shadowRgb[k]);
      reflection.setRgb(x, y, b.reflectionRgb[k]);
      refraction.setRgb(x, y, b.refractionRgb[k]);
      traced.setRgb(
          x, y,
          Vec3(b.want[k][0] ? 1.0f : 0.0f, b.want[k][1] ? 1.0f : 0.0f, b.want[k][2] ? 1.0f : 0.0f));
      continue;
    }
    Buffer* out[kEffectCount] = {&shadow, &reflection, &refraction};
    const Vec3 value[kEffectCount] = {b.shadowRgb[k], b.reflectionRgb[k], b.refractionRgb[k]};
    for (int e = 0; e < kEffectCount; ++e)
      if (b.want[k][e]) {
        out[e]->setRgb(x, y, value[e]);
        traced.at(x, y)[e] = 1.0f;
      }
  }
}

// The per-object tallies of every worker summed into the frame's statistics.
RtStats gatherStats(tbb::combinable<EffectTallies>& tallies, size_t objects, bool timed,
                    double msPerTick) {
  RtStats stats;
  stats.timeEffects = timed;
  stats.pixels.assign(objects, {});
  stats.rays.assign(objects, {});
  stats.cpuMs.assign(objects, {});
  tallies.combine_each([&](const EffectTallies& tally) {
    for (size_t o = 0; o < objects; ++o)
      for (size_t e = 0; e < size_t(kEffectCount); ++e) {
        stats.pixels[o][e] += tally[o].pixels[e];
        stats.rays[o][e] += tally[o].rays[e];
        stats.cpuMs[o][e] += double(tally[o].ticks[e]) * msPerTick;
      }
  });
  return stats;
}

}  // namespace

std::vector<CounterDesc> RTSecondaryPass::counters() const {
  std::vector<CounterDesc> c = whittedCounters(*this);
  c.insert(c.end(), {
                        {RTSecondaryCounters::itemsCut,
                         "ranked tiles left untraced at the deadline (with a deadline)"},
                    });
  return c;
}

void RTSecondaryPass::execute(FrameContext& ctx) {
  const auto start = Clock::now();
  const TickRate tickRate;
  RayTracer& rt = ctx.rayTracer();
  const uint64_t raysBefore = rt.raysTraced();
  const Scene& scene = *ctx.scene;
  const size_t objects = scene.objects.size();
  const ShadingContext shading = ShadingContext::from(scene);
  const WhittedSettings ws = settings().whitted.settings();
  Whitted whitted(rt, scene, shading, ws);
  // Classified shadows (and culled rays) of whole tiles go structure of arrays (shadow_tile.h);
  // every shadow traced without culling keeps the per-block path, exactly as it always drew.
  const bool tiled = ws.shadows != ShadowMode::Rays || ws.shadowCull > 0;
  ShadowTally shadowTally;
  const GBufferReader g = gbufferSource(ctx, *this);
  // Maps only for the lights that reach a surface in view: no other is ever asked about here.
  const std::vector<uint8_t> inView =
      ws.shadows != ShadowMode::Rays ? lightsInView(ctx.views, g, shading) : std::vector<uint8_t>{};
  const ShadowMaps* shadowMaps = shadowMapsFor(ctx, *this, settings().whitted, &inView);
  whitted.useShadowMaps(shadowMaps);
  whitted.countShadows(&shadowTally);
  // Classified shadows per pixel (viewer / AOV): R traced, G lit, B shadowed, as shares of the
  // lights that reach the pixel (or the one light asked for); 0 where no shadow was asked.
  Buffer* classOut = ctx.outputIfConsumed(*this, Slots::shadowClass);
  if (classOut) std::fill(classOut->data.begin(), classOut->data.end(), 0.0f);
  const int classLight = settings().shadowClassLight;
  const Buffer& mask = ctx.input(*this, Slots::heuristicMask);
  const RtRequest* request = ctx.inputRecord<RtRequest>(*this, Slots::rtRequest);
  const bool timed = request && request->timeEffects;
  const double deadlineMs = request ? request->deadlineMs : 0.0;
  tbb::combinable<EffectTallies> tallies([&] { return EffectTallies(objects); });
  const Buffer& ids = ctx.input(*this, Slots::objectId);
  const Buffer* order = ctx.optionalInput(*this, Slots::heuristicOrder);
  const SecondaryTrace job{scene,
                           shading,
                           rt,
                           whitted,
                           g,
                           mask,
                           ids,
                           order,
                           ctx.output(*this, Slots::shadow),
                           ctx.output(*this, Slots::reflection),
                           ctx.output(*this, Slots::refraction),
                           ctx.output(*this, Slots::tracedMask),
                           classOut,
                           classLight,
                           settings().outsideMaskShadow,
                           timed,
                           tiled};
  const ShadowTile tileJob{g,     &mask,      ids,      ctx.input(*this, Slots::geoNormal),
                           scene, shading,    &rt,      shadowMaps,
                           ws,    job.shadow, classOut, classLight,
                           timed, order};
  // `rank` < 0: every masked effect, every output written. Otherwise (a deadline's work item) only
  // the effects of that node rank, and only their outputs (the tile was cleared beforehand).
  auto traceTile = [&](const View& v, int x0, int y0, int x1, int y1, int64_t rank) {
    LightVisibility8 vis(scene.lights.size());
    std::vector<uint8_t> classes(classOut ? 8 * scene.lights.size() : 0);
    EffectTally* tally = tallies.local().data();
    // 4x2 pixel blocks: a block's shadow rays go as 8-wide packets, its shadow shading as one
    // batch.
    for (int by = y0; by < y1; by += 2)
      for (int bx = x0; bx < x1; bx += 4)
        job.traceBlock(v, bx, by, x1, y1, rank, tally, vis, classes);
    if (tiled) classifiedShadowTile(tileJob, v, x0, y0, x1, y1, rank, tally, shadowTally.local());
  };
  Clock::time_point deadline{};
  if (deadlineMs > 0) {
    // The deadline leaves room for the tail measured last time: the tiles in flight when it
    // passed and what follows them here.
    deadline = start + std::chrono::duration_cast<Clock::duration>(
                           std::chrono::duration<double, std::milli>(deadlineMs - tailMs_));
    const std::vector<RankedTile> queue =
        rankTiles(ctx.views, mask, ids, order,
                  [&](int x0, int y0, int x1, int y1) { job.clearTile(x0, y0, x1, y1); });
    const size_t cut = traceUntilDeadline(queue, deadline, traceTile);
    ctx.report(*this, RTSecondaryCounters::itemsCut, double(cut));
    if (cut == 0) deadline = {};  // nothing was cut: the tail says nothing
  } else {
    parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
      traceTile(v, x0, y0, x1, y1, -1);
    });
  }
  RtStats stats = gatherStats(tallies, objects, timed, 1.0 / tickRate.ticksPerMs());
  stats.ms = msSince(start);
  if (deadline != Clock::time_point{}) {
    const double tail =
        std::max(0.0, std::chrono::duration<double, std::milli>(Clock::now() - deadline).count());
    tailMs_ = std::min(0.5 * tailMs_ + 0.5 * tail, 0.5 * deadlineMs);
  }
  ctx.outputRecord<RtStats>(*this, Slots::rtStats) = std::move(stats);
  reportShadows(ctx, *this, sum(shadowTally), double(ctx.width) * double(ctx.height));
  ctx.passRays += double(rt.raysTraced() - raysBefore);
}

void RTSecondaryPass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  const WhittedSettings w = settings().whitted.settings();
  const size_t objects = ctx.scene->objects.size();
  SecondaryArgs a{};
  a.scene = gpu.scene(ctx.frame).sceneAddress();
  a.sources = gbufferDeviceSources(ctx, *this);
  a.mask = ctx.deviceInput(*this, Slots::heuristicMask);
  a.shadow = ctx.deviceOutput(*this, Slots::shadow);
  a.reflection = ctx.deviceOutput(*this, Slots::reflection);
  a.refraction = ctx.deviceOutput(*this, Slots::refraction);
  a.traced = ctx.deviceOutput(*this, Slots::tracedMask);
  a.shadowClass = ctx.deviceOutputIfConsumed(*this, Slots::shadowClass);
  // Counters, then rt_stats' tallies per object.
  const std::vector<uint32_t> zero(TD_COUNT_N + objects * TD_STATS_PER_OBJECT, 0);
  a.counters = gpu.constants(zero.data(), zero.size() * sizeof(uint32_t));
  // Classified and shadow-map shadows: the frame's maps, for the lights that reach a surface in
  // view (found on the device, back after a checkpoint), drawn there where they changed.
  std::vector<uint8_t> inView;
  if (settings().whitted.shadows != ShadowMode::Rays) {
    const uint32_t* flags = recordLightsInView(ctx, *this);
    gpu.commands().checkpoint();
    inView = wantedLights(flags, ctx.scene->lights.size());
  }
  const ShadowMaps* maps = shadowMapsFor(ctx, *this, settings().whitted, &inView, true);
  a.shadowMaps = maps ? gpuShadowMaps(ctx, *maps) : 0;
  a.frameWidth = ctx.width;
  a.maxDepth = w.maxDepth;
  a.importanceCutoff = w.importanceCutoff;
  a.shadowCull = w.shadowCull;
  a.outsideShadow = settings().outsideMaskShadow;
  a.flags = gpuWhittedFlags(w, maps != nullptr);
  a.classLight = settings().shadowClassLight;
  const GpuKernel& k = gpu.kernel("rt_secondary", kRtSecondarySpv, sizeof(kRtSecondarySpv) / 4,
                                  sizeof(SecondaryArgs));
  GpuCommands& cmd = gpu.commands();
  const uint32_t t0 = cmd.timestamp();
  for (const View& v : ctx.views) {
    a.view = gpuViewConstants(ctx, v);
    a.viewX = v.x;
    a.viewY = v.y;
    gpu.dispatchInterruptibly(k, uint32_t(v.width() + 7) / 8, uint32_t(v.height() + 7) / 8, &a);
  }
  const uint32_t t1 = cmd.timestamp();
  const RtRequest* request = ctx.inputRecord<RtRequest>(*this, Slots::rtRequest);
  const bool timed = request && request->timeEffects;
  if (request && request->deadlineMs > 0) ctx.report(*this, RTSecondaryCounters::itemsCut, 0.0);
  // Counters and tallies are read once the frame's commands completed.
  const auto* counts = static_cast<const uint32_t*>(gpu.constantsData(a.counters));
  const uint32_t* tallies = counts + TD_COUNT_N;
  const double pixels = double(ctx.width) * double(ctx.height);
  gpu.afterSubmit([this, &ctx, &cmd, counts, tallies, objects, timed, pixels, t0, t1] {
    reportGpuShadows(ctx, *this, counts, pixels);
    RtStats stats;
    stats.timeEffects = timed;
    stats.ms = cmd.activeMs(t0, t1);
    stats.pixels.assign(objects, {});
    stats.rays.assign(objects, {});
    stats.cpuMs.assign(objects, {});
    const double allRays = std::max(1.0, double(counts[TD_COUNT_RAYS]));
    for (size_t o = 0; o < objects; ++o)
      for (size_t e = 0; e < size_t(kEffectCount); ++e) {
        const uint32_t* t = tallies + o * TD_STATS_PER_OBJECT;
        stats.pixels[o][e] = t[e];
        stats.rays[o][e] = t[kEffectCount + e];
        // The GPU has no clock per object: the pass's time shared by each one's rays.
        if (timed) stats.cpuMs[o][e] = stats.ms * double(t[kEffectCount + e]) / allRays;
      }
    ctx.outputRecord<RtStats>(*this, Slots::rtStats) = std::move(stats);
  });
}

}  // namespace tandem
