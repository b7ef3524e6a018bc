#include "passes/common/deferred_shading.h"

#include <algorithm>

#include "gpu/shaders/deferred_shading_spv.h"
#include "passes/common/gpu_shadow_maps.h"
#include "passes/common/lights_in_view.h"
#include "passes/common/shadow_map_params.h"
#include "passes/common/whitted_settings.h"
#include "passes/heuristic/shadow_tile.h"
#include "pipeline/frame_context.h"
#include "pipeline/gbuffer_io.h"
#include "pipeline/gpu_frame.h"
#include "pipeline/gpu_gbuffer.h"
#include "pipeline/view_tiles.h"
#include "shading/batch_shader.h"

namespace tandem {

const ParamTable<DeferredSettings>& DeferredShadingPass::tableFor() const {
  using S = DeferredSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::shadows, {.name = "shadows",
                             .doc = "off (Listing 5: unshadowed; traced or fallback shadows come "
                                    "later) or the frame's raster shadow maps",
                             .choices = {"off", "shadow_map"}})
          .add(&S::shadowMapSize, shadowMapSizeParam())
          .add(&S::shadowMapFit, shadowMapFitParam())
          .add(&S::shadowCull, {.name = "shadow_cull",
                                .min = 0,
                                .max = 1,
                                .doc = "no shadow for a light below this share of a pixel's "
                                       "irradiance (0: every light that reaches it)"});
  return table;
}

std::vector<BufferSlot> DeferredShadingPass::inputs() const {
  return gbufferSampleSlots();
}

std::vector<CounterDesc> DeferredShadingPass::counters() const {
  return {{DeferredCounters::shadowMapRedraws,
           "shadow maps redrawn so far (with shadows = shadow_map)"}};
}

void DeferredShadingPass::executeShadowed(FrameContext& ctx) {
  const DeferredSettings& s = settings();
  const GBufferReader g = gbufferSource(ctx, *this);
  Buffer& hdr = ctx.output(*this, Slots::hdr);
  const Buffer& ids = ctx.input(*this, Slots::objectId);
  const Scene& scene = *ctx.scene;
  const ShadingContext shading = ShadingContext::from(scene);
  const auto t0 = Clock::now();
  // Maps only for the lights that reach a surface in view: no other is ever asked about.
  const std::vector<uint8_t> inView = lightsInView(ctx.views, g, shading);
  ShadowMaps& maps =
      ctx.shadowMaps(ctx.shadowMapResolution(s.shadowMapSize, s.shadowMapFit), &inView);
  ctx.passParts.push_back({"shadow_maps", msSince(t0), 0});
  WhittedSettings ws;
  ws.shadows = ShadowMode::Maps;
  ws.shadowCull = s.shadowCull;
  // Each pixel's light weighed once per light, the maps deciding every light that reaches the
  // cull floor, L - (1 - S) written: what ss_fallback's map shadows and blend made of it.
  const ShadowTile job{.g = g,
                       .mask = nullptr,
                       .ids = ids,
                       .geoNormal = ctx.input(*this, Slots::geoNormal),
                       .scene = scene,
                       .shading = shading,
                       .rt = nullptr,
                       .maps = &maps,
                       .settings = ws,
                       .shadow = hdr,
                       .classes = nullptr,
                       .classLight = -1,
                       .timed = false,
                       .order = nullptr,
                       .shadowChannel = 0,
                       .shadedRadiance = true};
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    const Camera& cam = v.jitteredCamera;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        if (ids.at(x, y)[0] >= 0) continue;
        Vec3 o, d;
        cam.generateRay(float(x - v.x) + 0.5f, float(y - v.y) + 0.5f, o, d);
        hdr.setRgb(x, y, scene.skyRadiance(d));
      }
    ShadowCounts counts;  // nothing traced: the maps' shares are not reported
    classifiedShadowTile(job, v, x0, y0, x1, y1, -1, nullptr, counts);
  });
  ctx.report(*this, DeferredCounters::shadowMapRedraws, maps.redraws());
}

void DeferredShadingPass::execute(FrameContext& ctx) {
  if (settings().shadows == DeferredSettings::Shadows::ShadowMap) return executeShadowed(ctx);
  const GBufferReader g = gbufferSource(ctx, *this);
  Buffer& hdr = ctx.output(*this, Slots::hdr);
  const Scene& scene = *ctx.scene;
  const ShadingContext shading = ShadingContext::from(scene);
  parallelViewTiles(ctx.views, [&](const View& v, int x0, int y0, int x1, int y1) {
    const Camera& cam = v.jitteredCamera;
    const bool perspective = cam.desc.projection == Projection::Perspective;
    BatchShader shader(shading, hdr);
    ShadeBatch& b = shader.batch();
    const Vec3 eye = perspective ? cam.eye : -cam.forward;
    constexpr int kSpan = ShadeBatch::kMax;
    for (int y = y0; y < y1; ++y)
      for (int xs = x0; xs < x1; xs += kSpan) {
        const int xe = std::min(xs + kSpan, x1);
        // A run of foreground pixels fills a whole batch in vectors; runs that touch the
        // background go pixel by pixel (the partial batch before a whole run is shaded first).
        if (xe - xs == kSpan) {
          shader.flush();
          Bounds3 lanes;
          if (g.readSpan(xs, y, kSpan, b, perspective, eye, lanes)) {
            shader.pushSpan(xs, y, kSpan, lanes);
            continue;
          }
        }
        for (int x = xs; x < xe; ++x) {
          const int lane = shader.lane();
          if (!g.read(x, y, b, lane)) {
            Vec3 o, d;
            cam.generateRay(float(x - v.x) + 0.5f, float(y - v.y) + 0.5f, o, d);
            hdr.setRgb(x, y, scene.skyRadiance(d));
            continue;
          }
          // The G-buffer point lies on the pixel's camera ray: the eye direction needs no ray.
          using F = ShadeBatch;
          const Vec3 p{b.f[F::PX][lane], b.f[F::PY][lane], b.f[F::PZ][lane]};
          const Vec3 wo = perspective ? normalize(eye - p) : eye;
          b.f[F::WX][lane] = wo.x, b.f[F::WY][lane] = wo.y, b.f[F::WZ][lane] = wo.z;
          shader.push(x, y);
        }
      }
  });
}

void DeferredShadingPass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  GBufferShadeArgs a{};
  a.scene = gpu.scene(ctx.frame).sceneAddress();
  a.targets = gbufferDeviceSources(ctx, *this);
  a.hdr = ctx.deviceOutput(*this, Slots::hdr);
  a.frameWidth = ctx.width;
  if (settings().shadows == DeferredSettings::Shadows::ShadowMap) {
    // The lights that reach a surface in view, back after a checkpoint, then their maps.
    const uint32_t* lightFlags = recordLightsInView(ctx, *this);
    gpu.commands().checkpoint();
    const std::vector<uint8_t> inView = wantedLights(lightFlags, ctx.scene->lights.size());
    const DeferredSettings& s = settings();
    const ShadowMaps& maps = deviceShadowMaps(
        ctx, *this, ctx.shadowMapResolution(s.shadowMapSize, s.shadowMapFit), &inView);
    a.shadowMaps = gpuShadowMaps(ctx, maps);
    a.shadowCull = s.shadowCull;
    ctx.report(*this, DeferredCounters::shadowMapRedraws, maps.redraws());
  }
  const GpuKernel& k = gpu.kernel("deferred_shading", kDeferredShadingSpv,
                                  sizeof(kDeferredShadingSpv) / 4, sizeof(GBufferShadeArgs));
  for (const View& v : ctx.views) {
    a.view = gpuViewConstants(ctx, v);
    a.viewX = v.x;
    a.viewY = v.y;
    gpu.commands().dispatch(k, uint32_t(v.width() + 7) / 8, uint32_t(v.height() + 7) / 8, 1, &a);
  }
}

}  // namespace tandem
