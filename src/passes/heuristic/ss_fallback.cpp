#include "passes/heuristic/ss_fallback.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>

#include "passes/heuristic/rt_feedback.h"
#include "pipeline/frame_context.h"
#include "pipeline/gbuffer_io.h"
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
          .add(&S::shadowMapSize,
               {.name = "shadow_map_size", .min = 64, .max = 8192, .doc = "shadow map resolution"})
          .add(&S::probeSize, {.name = "probe_size",
                               .min = 8,
                               .max = 1024,
                               .doc = "reflection probe face resolution"})
          .add(&S::maxProbes,
               {.name = "max_probes",
                .min = 0,
                .max = 4096,
                .doc = "most objects with a probe (the largest on screen; others show the sky)"})
          .add(&S::probeRefresh,
               {.name = "probe_refresh",
                .min = 0,
                .max = 1024,
                .doc =
                    "probes redrawn per frame when geometry moved (oldest first; new ones always)"})
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
  in.push_back({"hdr", 3});
  in.push_back(effectSlot("heuristic_mask", BufferKind::Mask));
  return in;
}

namespace {

struct Frame {
  const Buffer &hdr, &position, &objectId, &optical;
  const Scene& scene;
  float reach;  // longest march: the scene's diagonal
};

// A pixel the shadow maps stand in for, and its view direction.
struct ShadowPixel {
  int x, y;
  Vec3 d;
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
  // A probe for every reflective or transparent object that shows an untraced effect.
  const auto t0 = Clock::now();
  const Scene& scene = *ctx.scene;
  const Buffer& optical = ctx.input(*this, "optical");
  const Buffer& objectId = ctx.input(*this, "object_id");
  const Buffer& mask = ctx.input(*this, "heuristic_mask");
  // At most max_probes of them, the largest on screen (the others show the sky): each probe
  // costs six draws of the scene and its memory.
  tbb::enumerable_thread_specific<std::vector<uint32_t>> areas(
      std::vector<uint32_t>(scene.objects.size(), 0));
  parallelRange(objectId.pixelCount(), [&](size_t b, size_t e) {
    std::vector<uint32_t>& local = areas.local();
    for (size_t i = b; i < e; ++i) {
      const float id = objectId.data[i];
      if (id < 0) continue;
      const float *op = &optical.data[OpticalChannels::kCount * i],
                  *m = &mask.data[size_t(kEffectCount) * i];
      if ((op[OpticalChannels::kReflectivity] > 0 && m[kReflection] < 0.5f) ||
          (op[OpticalChannels::kOpacity] < 1 && m[kRefraction] < 0.5f))
        ++local[size_t(id)];
    }
  });
  std::vector<uint32_t> area(scene.objects.size(), 0);
  for (const std::vector<uint32_t>& local : areas)
    for (size_t o = 0; o < area.size(); ++o) area[o] += local[o];
  std::vector<uint32_t> order;
  for (size_t o = 0; o < area.size(); ++o)
    if (area[o] > 0) order.push_back(uint32_t(o));
  const FallbackSettings& s = settings();
  const size_t keep = std::min(order.size(), size_t(s.maxProbes));
  std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(keep), order.end(),
                    [&](uint32_t a, uint32_t c) { return area[a] > area[c]; });
  std::vector<uint8_t> wanted(scene.objects.size(), 0);
  for (size_t k = 0; k < keep; ++k) wanted[order[k]] = 1;
  ctx.report(*this, FallbackCounters::probesDrawn,
             probes_.update(ctx.frame, shading, wanted, s.probeSize, s.probeRefresh,
                            2 * size_t(s.maxProbes)));
  ctx.passParts.push_back({"probes", msSince(t0), 0});
}

namespace {

// The occluded fraction of each light at each pixel (occluded[light * count + pixel]). A light
// the surface faces away from, or that does not reach it, adds nothing whatever its map says: no
// lookup. Looked up 16 points at a time (the SIMD kernel), light by light; only the position and
// the two normals are read.
std::vector<float> occludedFractions(const std::vector<ShadowPixel>& shadowed,
                                     const Buffer& position, const Buffer& normal,
                                     const Buffer& geoNormal, const ShadingContext& shading,
                                     const ShadowMaps& maps, size_t lights) {
  const size_t count = shadowed.size();
  std::vector<float> occluded(lights * count);
  constexpr size_t W = 16;
  for (size_t k0 = 0; k0 < count; k0 += W) {
    const size_t n = std::min(W, count - k0);
    float px[W] = {}, py[W] = {}, pz[W] = {}, nx[W] = {}, ny[W] = {}, nz[W] = {};
    Vec3 shadingNormal[W];
    for (size_t k = 0; k < n; ++k) {
      const int x = shadowed[k0 + k].x, y = shadowed[k0 + k].y;
      const float *p = position.at(x, y), *gn = geoNormal.at(x, y);
      px[k] = p[0], py[k] = p[1], pz[k] = p[2];
      nx[k] = gn[0], ny[k] = gn[1], nz[k] = gn[2];
      shadingNormal[k] = normal.rgb(x, y);
    }
    for (size_t i = 0; i < lights; ++i) {
      float lit[W] = {}, vis[W] = {};
      for (size_t k = 0; k < n; ++k) {
        const LightSample ls = sampleLight(shading.lights[i], {px[k], py[k], pz[k]});
        lit[k] = dot(shadingNormal[k], ls.wi) > 0.0f && maxComponent(ls.radiance) > 0.0f;
      }
      maps.visibilityBatch(i, px, py, pz, nx, ny, nz, lit, int(n), vis);
      for (size_t k = 0; k < n; ++k)
        occluded[i * count + k0 + k] = lit[k] > 0 ? 1.0f - vis[k] : 0.0f;
    }
  }
  return occluded;
}

// As rt_secondary (Listing 8a): S = 1 - the light the occluders block, from one shading call
// weighted by each light's occluded fraction. Pixels no map shadows keep S = 1 unshaded, and a
// batch evaluates only the lights that shadow one of its lanes (the others add exactly 0).
void shadeShadows(const std::vector<ShadowPixel>& shadowed, const std::vector<float>& occluded,
                  const GBufferReader& g, const ShadingContext& shading, size_t lights,
                  Buffer& out) {
  using F = ShadeBatch;
  const size_t count = shadowed.size();
  ShadeBatch batch;
  std::vector<float> blocked(3 * lights * ShadeBatch::kMax);
  std::vector<uint32_t> batchLights;
  batchLights.reserve(lights);
  size_t lane[ShadeBatch::kMax];
  auto flush = [&] {
    batchLights.clear();
    for (size_t i = 0; i < lights; ++i)
      for (int j = 0; j < batch.count; ++j)
        if (occluded[i * count + lane[j]] > 0.0f) {
          batchLights.push_back(uint32_t(i));
          break;
        }
    for (uint32_t i : batchLights)
      for (int j = 0; j < batch.count; ++j)
        for (size_t c = 0; c < 3; ++c)
          blocked[(3 * i + c) * ShadeBatch::kMax + size_t(j)] = occluded[i * count + lane[j]];
    batch.lights = batchLights.data();
    batch.lightCount = batchLights.size();
    shadeBatch(batch, shading, blocked.data(), ShadeBatch::kMax);
    for (int j = 0; j < batch.count; ++j) {
      const Vec3 s = shadowFromBlocked(batch, j, shading.ambient);
      float* px = out.at(shadowed[lane[j]].x, shadowed[lane[j]].y) + fallback::kShadow;
      px[0] = s.x, px[1] = s.y, px[2] = s.z;
    }
    batch.count = 0;
  };
  batch.count = 0;
  for (size_t k = 0; k < count; ++k) {
    float* px = out.at(shadowed[k].x, shadowed[k].y);
    px[fallback::kCoversShadow] = 1.0f;
    bool any = false;
    for (size_t i = 0; i < lights; ++i) any |= occluded[i * count + k] > 0.0f;
    if (!any) {
      px[fallback::kShadow] = px[fallback::kShadow + 1] = px[fallback::kShadow + 2] = 1.0f;
      continue;
    }
    // The G-buffer straight into the lane (as deferred shading reads it); the viewer is -d.
    const int l = batch.count;
    g.read(shadowed[k].x, shadowed[k].y, batch, l);
    const Vec3 wo = -shadowed[k].d;
    batch.f[F::WX][l] = wo.x, batch.f[F::WY][l] = wo.y, batch.f[F::WZ][l] = wo.z;
    lane[batch.count++] = k;
    if (batch.count == ShadeBatch::kMax) flush();
  }
  if (batch.count) flush();
}

struct EffectsJob {
  const Frame& f;
  const Buffer &normal, &mask;
  FallbackMode mode;
  bool shadows;
  const ReflectionProbes& probes;
  Bounds3 bounds;
  int steps;
  float thickness;
};

// Writes what stands in for the tile's untraced reflections and refractions, and lists the
// pixels whose untraced shadow the maps stand in for.
void effectsTile(const EffectsJob& job, const View& v, int x0, int y0, int x1, int y1, Buffer& out,
                 std::vector<ShadowPixel>& shadowed) {
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
      const bool shadow = job.shadows && m[kShadow] < 0.5f;
      if (!reflect && !refract && !shadow) continue;
      Vec3 o, d;
      v.jitteredCamera.generateRay(float(x - v.x) + 0.5f, float(y - v.y) + 0.5f, o, d);
      if (shadow) shadowed.push_back({x, y, d});
      if (!reflect && !refract) continue;
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
  const Buffer& position = ctx.input(*this, "position");
  const Buffer& normal = ctx.input(*this, "normal");
  const Buffer& geoNormal = ctx.input(*this, "geo_normal");
  Buffer& out = ctx.output(*this, "fallback");
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
  ShadowMaps* shadowMaps = nullptr;
  if (shadows) {
    const auto t0 = Clock::now();
    shadowMaps = &ctx.shadowMaps(s.shadowMapSize);
    ctx.passParts.push_back({"shadow_maps", msSince(t0), 0});
  }
  const ShadingContext shading = ShadingContext::from(scene);
  if (mode == FallbackMode::Probe) updateProbes(ctx, shading);
  const Bounds3 b = scene.bounds(ctx.frame.time);
  const Frame f{ctx.input(*this, "hdr"),     position, ctx.input(*this, "object_id"),
                ctx.input(*this, "optical"), scene,    std::max(length(b.hi - b.lo), 0.1f)};
  const EffectsJob job{f,    normal,  ctx.input(*this, "heuristic_mask"),
                       mode, shadows, probes_,
                       b,    s.steps, s.thickness};
  const size_t lights = scene.lights.size();
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    // The tile's shadow pixels are gathered first and looked up light by light (one map's texels
    // stay in cache across the tile), then shaded in batches: per light and channel a row of
    // lanes holding the occluded fraction (rt_secondary's Listing 8a sum, 16 pixels at a time).
    std::vector<ShadowPixel> shadowed;
    shadowed.reserve(size_t(x1 - x0) * size_t(y1 - y0));
    effectsTile(job, v, x0, y0, x1, y1, out, shadowed);
    if (shadowed.empty()) return;
    const std::vector<float> occluded =
        occludedFractions(shadowed, position, normal, geoNormal, shading, *shadowMaps, lights);
    shadeShadows(shadowed, occluded, g, shading, lights, out);
  });
  if (shadowMaps) ctx.report(*this, FallbackCounters::shadowMapRedraws, shadowMaps->redraws());
}

}  // namespace tandem
