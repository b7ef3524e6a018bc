#include "passes/heuristic/ss_fallback.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "gpu/shaders/fallback_args.h"
#include "gpu/shaders/fallback_spv.h"
#include "passes/common/gpu_shadow_maps.h"
#include "passes/common/lights_in_view.h"
#include "passes/common/shadow_map_params.h"
#include "passes/heuristic/gpu_reflection_probes.h"
#include "passes/heuristic/rt_feedback.h"
#include "passes/heuristic/shadow_tile.h"
#include "pipeline/frame_context.h"
#include "pipeline/gbuffer_io.h"
#include "pipeline/gpu_frame.h"
#include "pipeline/gpu_gbuffer.h"
#include "pipeline/view_tiles.h"
#include "rt/whitted.h"
#include "shading/gbuffer_layout.h"
#include "shading/shade_batch.h"

namespace tandem {

namespace {
using FallbackMode = FallbackSettings::Mode;
}

const ParamTable<FallbackSettings>& ScreenSpaceFallbackPass::tableFor() const {
  using S = FallbackSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(
              &S::mode,
              {.name = "mode",
               .doc = "unselected reflections/refractions: off (Walewski et al. 2019: black), sky, "
                      "screen space, per-object reflection probes",
               .choices = {"off", "environment", "screen_space", "probe"}})
          .add(&S::shadows, {.name = "shadows",
                             .doc = "unselected shadows: off (Walewski et al. 2019: unshadowed) or "
                                    "raster shadow maps",
                             .choices = {"off", "shadow_map"}})
          .add(&S::shadowMapSize, shadowMapSizeParam())
          .add(&S::shadowMapFit, shadowMapFitParam())
          .add(&S::shadowCull,
               {.name = "shadow_cull",
                .min = 0,
                .max = 1,
                .doc = "no shadow for a light below this share of a pixel's irradiance (as "
                       "rt_secondary culls its shadow rays; 0: every light that reaches it)"})
          .add(&S::probeSize, {.name = "probe_size",
                               .min = 8,
                               .max = 1024,
                               .doc = "reflection probe face resolution"})
          .add(&S::maxProbes,
               {.name = "max_probes",
                .min = 0,
                .max = 4096,
                .doc = "most objects with a probe (those showing the most untraced pixels, then "
                       "the largest in view; others show the sky)"})
          .add(&S::probeRefresh,
               {.name = "probe_refresh",
                .min = 0,
                .max = 1024,
                .doc =
                    "probes redrawn per frame when geometry moved (oldest first; new ones always)"})
          .add(&S::probeBake,
               {.name = "probe_bake",
                .doc = "the first frame draws a probe for every mirror and glass object (up to "
                       "max_probes, the largest first), as engines bake static probes at load, "
                       "so an object entering the view finds its probe drawn; off: drawn when "
                       "the object first shows"})
          .add(
              &S::steps,
              {.name = "steps", .min = 1, .max = 512, .doc = "march steps along the reflected ray"})
          .add(&S::thickness,
               {.name = "thickness",
                .min = 0,
                .max = 100,
                .doc = "depth a surface is taken to have, as a fraction of the distance marched"});
  return table;
}

std::vector<BufferSlot> ScreenSpaceFallbackPass::inputs() const {
  std::vector<BufferSlot> in = gbufferSampleSlots();
  in.push_back({Slots::hdr, 3});
  in.push_back(effectSlot(Slots::heuristicMask, BufferKind::Mask));
  return in;
}

namespace {

struct Frame {
  const Buffer &hdr, &position, &objectId, &optical;
  const Scene& scene;
  float reach;  // longest march: the scene's diagonal
};

// Colour seen from p along unit direction r in view v: the first frame pixel whose surface the
// march passes just behind (skipping `self` for refraction), else the sky.
// A refraction march (self >= 0) takes the first surface it passes behind, however far: the
// front faces hide where the ray would leave the object.
Vec3 marchScreen(const Frame& f, const View& v, Vec3 p, Vec3 r, int steps, float thickness,
                 int self) {
  const Camera& cam = v.jitteredCamera;
  // Clip coordinates and view depth are affine in t along the ray: one matrix product each for
  // the start and the direction, then a few multiply-adds a step.
  const Vec4 c0 = cam.viewProj * Vec4(p, 1.0f), cr = cam.viewProj * Vec4(r, 0.0f);
  const float z0 = dot(p - cam.eye, cam.forward), zr = dot(r, cam.forward);
  // Geometric steps: fine near the surface, coarse far away.
  const float growth = std::pow(f.reach / 0.01f, 1.0f / float(std::max(steps - 1, 1)));
  float t = 0.01f;
  for (int i = 0; i < steps; ++i, t *= growth) {
    const Vec4 c = c0 + cr * t;
    if (c.w <= 1e-6f) break;  // behind the eye
    const float iw = 1.0f / c.w;
    const float sx = (c.x * iw * 0.5f + 0.5f) * float(cam.width);
    const float sy = (0.5f - c.y * iw * 0.5f) * float(cam.height);
    if (!(sx >= 0 && sy >= 0 && sx < float(cam.width) && sy < float(cam.height))) break;
    const int fx = int(sx) + v.x, fy = int(sy) + v.y;
    const int id = int(f.objectId.at(fx, fy)[0]);
    if (id < 0 || id == self) continue;
    const float surface = dot(f.position.rgb(fx, fy) - cam.eye, cam.forward);
    const float behind = z0 + zr * t - surface;
    if (behind > 0 && (self >= 0 || behind < thickness * t + 0.02f)) {
      // A mirror or glass pixel's raster colour is not what it shows: the sky stands in.
      const float* op = f.optical.at(fx, fy);
      if (op[OpticalChannels::kReflectivity] > 0 || op[OpticalChannels::kOpacity] < 1) break;
      return f.hdr.rgb(fx, fy);
    }
  }
  return f.scene.skyRadiance(r);
}

}  // namespace

void ScreenSpaceFallbackPass::updateProbes(FrameContext& ctx, const ShadingContext& shading) {
  // A probe for every reflective or transparent object in view, those that show an untraced
  // effect first.
  const auto t0 = Clock::now();
  const Scene& scene = *ctx.scene;
  const Buffer& optical = ctx.input(*this, Slots::optical);
  const Buffer& objectId = ctx.input(*this, Slots::objectId);
  const Buffer& mask = ctx.input(*this, Slots::heuristicMask);
  const size_t n = scene.objects.size();
  tbb::enumerable_thread_specific<std::vector<uint32_t>> areas(std::vector<uint32_t>(2 * n, 0));
  parallelRange(objectId.pixelCount(), [&](size_t b, size_t e) {
    std::vector<uint32_t>& local = areas.local();
    for (size_t i = b; i < e; ++i) {
      const float id = objectId.data[i];
      if (id < 0) continue;
      const float *op = &optical.data[OpticalChannels::kCount * i],
                  *m = &mask.data[size_t(kEffectCount) * i];
      const bool reflective = op[OpticalChannels::kReflectivity] > 0,
                 transparent = op[OpticalChannels::kOpacity] < 1;
      if ((reflective && m[kReflection] < 0.5f) || (transparent && m[kRefraction] < 0.5f))
        ++local[size_t(id)];
      if (reflective || transparent) ++local[n + size_t(id)];
    }
  });
  std::vector<uint32_t> area(2 * n, 0);
  for (const std::vector<uint32_t>& local : areas)
    for (size_t o = 0; o < area.size(); ++o) area[o] += local[o];
  updateProbes(ctx, shading, area, probes_);
  ctx.passParts.push_back({"probes", msSince(t0), 0});
}

void ScreenSpaceFallbackPass::updateProbes(FrameContext& ctx, const ShadingContext& shading,
                                           const std::vector<uint32_t>& area,
                                           ReflectionProbes& probes) {
  // The heuristic's selection changes from frame to frame while the objects in view stay: an
  // object traced now is wanted too, so that its probe is there (drawn once; probes do not depend
  // on the camera) the frame the selection leaves it out, instead of drawn in that frame.
  const size_t n = area.size() / 2;
  const uint32_t* untraced = area.data();
  const uint32_t* inView = area.data() + n;
  std::vector<uint32_t> order;
  for (size_t o = 0; o < n; ++o)
    if (inView[o] > 0) order.push_back(uint32_t(o));
  const FallbackSettings& s = settings();
  const size_t keep = std::min(order.size(), size_t(s.maxProbes));
  // At most max_probes of them: those showing the most untraced pixels, then the largest in view
  // (the others show the sky). Each probe costs six draws of the scene and its memory.
  std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(keep), order.end(),
                    [&](uint32_t a, uint32_t c) {
                      return untraced[a] != untraced[c] ? untraced[a] > untraced[c]
                                                        : inView[a] > inView[c];
                    });
  std::vector<uint8_t> wanted(n, 0);
  for (size_t k = 0; k < keep; ++k) wanted[order[k]] = 1;
  if (s.probeBake && probes.updates() == 0) {
    // The first frame bakes the rest too, the largest first: probes do not depend on the camera,
    // so a later frame whose camera turns to an object finds its probe drawn instead of paying
    // six draws of the scene then. The images are the same.
    const Scene& scene = *ctx.scene;
    std::vector<uint32_t> rest;
    for (size_t o = 0; o < n && o < scene.objects.size(); ++o) {
      const Material& m = scene.materials[size_t(scene.objects[o].material)];
      if (!wanted[o] && (m.reflectivity > 0 || m.opacity < 1)) rest.push_back(uint32_t(o));
    }
    auto extent = [&](uint32_t o) {
      const Bounds3& b = ctx.frame.objects[o].bounds;
      return length(b.hi - b.lo);
    };
    std::stable_sort(rest.begin(), rest.end(),
                     [&](uint32_t a, uint32_t c) { return extent(a) > extent(c); });
    for (size_t k = 0; keep + k < size_t(s.maxProbes) && k < rest.size(); ++k) wanted[rest[k]] = 1;
  }
  ctx.report(*this, FallbackCounters::probesDrawn,
             probes.update(ctx.frame, shading, wanted, s.probeSize, s.probeRefresh,
                           2 * size_t(s.maxProbes)));
}

namespace {

struct EffectsJob {
  const Frame& f;
  const Buffer &normal, &mask;
  FallbackMode mode;
  const ReflectionProbes& probes;
  Bounds3 bounds;
  int steps;
  float thickness;
};

// Writes what stands in for the tile's untraced reflections and refractions.
void effectsTile(const EffectsJob& job, const View& v, int x0, int y0, int x1, int y1,
                 Buffer& out) {
  const Frame& f = job.f;
  const FallbackMode mode = job.mode;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const int id = int(f.objectId.at(x, y)[0]);
      if (id < 0) continue;
      const float* op = f.optical.at(x, y);
      const float* m = job.mask.at(x, y);
      const bool reflect = mode != FallbackMode::Off && op[OpticalChannels::kReflectivity] > 0 &&
                           m[kReflection] < 0.5f;
      const bool refract =
          mode != FallbackMode::Off && op[OpticalChannels::kOpacity] < 1 && m[kRefraction] < 0.5f;
      if (!reflect && !refract) continue;
      Vec3 o, d;
      v.jitteredCamera.generateRay(float(x - v.x) + 0.5f, float(y - v.y) + 0.5f, o, d);
      const Vec3 p = f.position.rgb(x, y);
      Vec3 n = job.normal.rgb(x, y);
      if (dot(n, d) > 0) n = -n;
      auto look = [&](Vec3 r, int self) {
        if (mode == FallbackMode::Probe) {  // refraction: out through the object first
          Vec3 from = p;
          const Vec3 dir =
              self < 0 ? r : job.probes.exitDirection(id, p, r, op[OpticalChannels::kIor], from);
          return job.probes.lookupFrom(f.scene, id, from, dir, job.bounds);
        }
        return mode == FallbackMode::Environment
                   ? f.scene.skyRadiance(r)
                   : marchScreen(f, v, p, r, job.steps, job.thickness, self);
      };
      float* px = out.at(x, y);
      if (reflect) {
        const Vec3 c = look(normalize(reflectDir(d, n)), -1);
        px[fallback::kReflection] = c.x, px[fallback::kReflection + 1] = c.y,
        px[fallback::kReflection + 2] = c.z;
      }
      if (refract) {
        // Entering the object (the G-buffer holds front faces): the refracted direction, the
        // object itself not counted as what lies behind it.
        Vec3 t;
        if (!refractDir(d, n, 1.0f / std::max(op[OpticalChannels::kIor], 1e-3f), t))
          t = reflectDir(d, n);
        const Vec3 c = look(t, id);
        px[fallback::kRefraction] = c.x, px[fallback::kRefraction + 1] = c.y,
        px[fallback::kRefraction + 2] = c.z;
      }
      px[fallback::kCoversEffect] = 1.0f;
    }
}

}  // namespace

std::vector<CounterDesc> ScreenSpaceFallbackPass::counters() const {
  return {
      {FallbackCounters::probesDrawn, "reflection probes (re)drawn this frame"},
      {FallbackCounters::shadowMapRedraws, "shadow maps redrawn so far (with shadow-map shadows)"},
  };
}

void ScreenSpaceFallbackPass::execute(FrameContext& ctx) {
  const FallbackSettings& s = settings();
  const FallbackMode mode = s.mode;
  const bool shadows = s.shadows == FallbackSettings::Shadows::ShadowMap;
  const GBufferReader g = gbufferSource(ctx, *this);
  const Buffer& position = ctx.input(*this, Slots::position);  // (hdr, position: the march)
  const Buffer& normal = ctx.input(*this, Slots::normal);
  const Buffer& geoNormal = ctx.input(*this, Slots::geoNormal);
  Buffer& out = ctx.output(*this, Slots::fallback);
  // 11 floats a pixel (40 MB at 720p): cleared in parallel, as one thread cannot write it fast.
  parallelRange(
      out.data.size(),
      [&](size_t b, size_t e) {
        std::fill(out.data.begin() + ptrdiff_t(b), out.data.begin() + ptrdiff_t(e), 0.0f);
      },
      size_t(1) << 16);
  if (mode == FallbackMode::Off && !shadows) return;
  const Scene& scene = *ctx.scene;
  // The frame's shared maps (classified shadows in rt_secondary drew them already when its
  // size is the same).
  const ShadingContext shading = ShadingContext::from(scene);
  ShadowMaps* shadowMaps = nullptr;
  if (shadows) {
    const auto t0 = Clock::now();
    // Maps only for the lights that reach a surface in view: no other is ever asked about here.
    const std::vector<uint8_t> inView = lightsInView(ctx.views, g, shading);
    shadowMaps = &ctx.shadowMaps(ctx.shadowMapResolution(s.shadowMapSize, s.shadowMapFit), &inView);
    ctx.passParts.push_back({"shadow_maps", msSince(t0), 0});
  }
  if (mode == FallbackMode::Probe) updateProbes(ctx, shading);
  const Bounds3 b = scene.bounds(ctx.frame.time);
  const Frame f{ctx.input(*this, Slots::hdr),     position, ctx.input(*this, Slots::objectId),
                ctx.input(*this, Slots::optical), scene,    std::max(length(b.hi - b.lo), 0.1f)};
  const Buffer& mask = ctx.input(*this, Slots::heuristicMask);
  const EffectsJob job{f, normal, mask, mode, probes_, b, s.steps, s.thickness};
  // Unselected shadows as rt_secondary's classified shadows with the maps deciding every pair
  // (the same culling of negligible lights, lookups 16 lanes at a time, S shaded only for the
  // lights something blocks), written into the fallback's shadow channels.
  WhittedSettings ws;
  ws.shadows = ShadowMode::Maps;
  ws.shadowCull = s.shadowCull;
  ShadowCounts counts;  // not reported: ss_fallback traces nothing
  const ShadowTile shadowJob{.g = g,
                             .mask = &mask,
                             .ids = ctx.input(*this, Slots::objectId),
                             .geoNormal = geoNormal,
                             .scene = scene,
                             .shading = shading,
                             .rt = nullptr,
                             .maps = shadowMaps,
                             .settings = ws,
                             .shadow = out,
                             .classes = nullptr,
                             .classLight = -1,
                             .timed = false,
                             .order = nullptr,
                             .unselected = true,
                             .shadowChannel = fallback::kShadow,
                             .coverChannel = fallback::kCoversShadow};
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    effectsTile(job, v, x0, y0, x1, y1, out);
    if (shadows) {
      ShadowCounts local;
      classifiedShadowTile(shadowJob, v, x0, y0, x1, y1, -1, nullptr, local);
    }
  });
  if (shadowMaps) ctx.report(*this, FallbackCounters::shadowMapRedraws, shadowMaps->redraws());
}

void ScreenSpaceFallbackPass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  GpuCommands& cmd = gpu.commands();
  const FallbackSettings& s = settings();
  const Scene& scene = *ctx.scene;
  const bool shadows = s.shadows == FallbackSettings::Shadows::ShadowMap;
  FallbackArgs a{};
  // (Both off: the kernel writes zeros, as the CPU pass clears its output.)
  a.result = ctx.deviceOutput(*this, Slots::fallback);
  a.scene = gpu.scene(ctx.frame).sceneAddress();
  a.sources = gbufferDeviceSources(ctx, *this);
  a.hdr = ctx.deviceInput(*this, Slots::hdr);
  a.mask = ctx.deviceInput(*this, Slots::heuristicMask);
  a.frameWidth = ctx.width;
  a.mode = int(s.mode);
  a.steps = s.steps;
  a.thickness = s.thickness;
  a.shadowCull = s.shadowCull;
  a.objectCount = uint32_t(scene.objects.size());
  const ShadingContext shading = ShadingContext::from(scene);
  const GpuKernel& k =
      gpu.kernel("fallback", kFallbackSpv, sizeof(kFallbackSpv) / 4, sizeof(FallbackArgs));
  const Bounds3 b = scene.bounds(ctx.frame.time);
  std::vector<uint64_t> views, marches;
  for (const View& v : ctx.views) {
    views.push_back(gpuViewConstants(ctx, v));
    FallbackView fv{};
    std::memcpy(fv.viewProj, &v.jitteredCamera.viewProj.m[0][0], sizeof fv.viewProj);
    fv.boundsLo[0] = b.lo.x, fv.boundsLo[1] = b.lo.y, fv.boundsLo[2] = b.lo.z;
    fv.boundsHi[0] = b.hi.x, fv.boundsHi[1] = b.hi.y, fv.boundsHi[2] = b.hi.z;
    fv.reach = std::max(length(b.hi - b.lo), 0.1f);
    fv.growth = std::pow(fv.reach / 0.01f, 1.0f / float(std::max(s.steps - 1, 1)));
    marches.push_back(gpu.constants(&fv, sizeof fv));
  }
  auto run = [&](int phase) {
    a.phase = phase;
    for (size_t i = 0; i < ctx.views.size(); ++i) {
      const View& v = ctx.views[i];
      a.view = views[i];
      a.march = marches[i];
      a.viewX = v.x;
      a.viewY = v.y;
      cmd.dispatch(k, uint32_t(v.width() + 7) / 8, uint32_t(v.height() + 7) / 8, 1, &a);
    }
  };
  // What the host needs before the maps and probes are drawn, back after one checkpoint: the
  // lights that reach a surface in view, each object's untraced pixels.
  const uint32_t* lightFlags = shadows ? recordLightsInView(ctx, *this) : nullptr;
  if (s.mode == FallbackMode::Probe) {
    const std::vector<uint32_t> zero(std::max<size_t>(2 * scene.objects.size(), 1), 0);
    a.areas = gpu.constants(zero.data(), zero.size() * sizeof(uint32_t));
    run(TD_FALLBACK_COUNT);
  }
  if (shadows || s.mode == FallbackMode::Probe) cmd.checkpoint();
  if (shadows) {
    const std::vector<uint8_t> inView = wantedLights(lightFlags, scene.lights.size());
    const ShadowMaps& maps = deviceShadowMaps(
        ctx, *this, ctx.shadowMapResolution(s.shadowMapSize, s.shadowMapFit), &inView);
    a.shadowMaps = gpuShadowMaps(ctx, maps);
    ctx.report(*this, FallbackCounters::shadowMapRedraws, maps.redraws());
  }
  if (s.mode == FallbackMode::Probe) {
    const auto* counted = static_cast<const uint32_t*>(gpu.constantsData(a.areas));
    drawProbesOnDevice(ctx, deviceProbes_);
    const uint32_t t0 = cmd.timestamp();
    updateProbes(ctx, shading, std::vector<uint32_t>(counted, counted + 2 * scene.objects.size()),
                 deviceProbes_);
    const uint32_t t1 = cmd.timestamp();
    gpu.afterSubmit([&ctx, &cmd, t0, t1] {
      ctx.passParts.push_back({"probes", cmd.activeMs(t0, t1), 0});
    });
    a.probes = gpuProbes(ctx, deviceProbes_);
  }
  run(TD_FALLBACK_WRITE);
}

}  // namespace tandem
