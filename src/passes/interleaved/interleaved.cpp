#include "passes/interleaved/interleaved.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>

#include "core/hash.h"
#include "core/parallel.h"
#include "passes/common/time_lens_camera.h"
#include "passes/common/whitted_settings.h"
#include "pipeline/frame_context.h"
#include "rt/reference_render.h"
#include "rt/whitted.h"
#include "shading/blinn_phong.h"
#include "shading/shade_batch.h"
#include "shading/surface_resolve.h"

namespace tandem {

float blackmanHarris(float t) {
  // The 4-term window over [-1, 1] (Harris 1978), centred: x in [0, 1] maps to 0.5 + t / 2.
  if (t >= 1.0f) return 0.0f;
  const float x = kPi * (1.0f + t);  // 2 pi (0.5 + t / 2)
  return 0.35875f - 0.48829f * std::cos(x) + 0.14128f * std::cos(2 * x) -
         0.01168f * std::cos(3 * x);
}

const ParamTable<InterleavedSettings>& InterleavedPass::tableFor() const {
  using S = InterleavedSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::samples, {.name = "samples",
                             .min = 1,
                             .max = 4096,
                             .doc = "N: (time, lens) pairs in T (passes)",
                             .invalidatesHistory = true})
          .add(&S::spp, {.name = "spp",
                         .min = 1,
                         .max = 64,
                         .doc = "k: samples per pixel (N must be a multiple)",
                         .invalidatesHistory = true})
          .add(&S::scheme,
               {.name = "scheme",
                .doc = "how samples take pairs of T",
                .choices = {"independent", "stratified", "random_tiles", "colored_corner"},
                .invalidatesHistory = true})
          .add(&S::mode, {.name = "mode",
                          .doc = "what the pairs vary",
                          .choices = {"dof", "motion_blur", "both"},
                          .invalidatesHistory = true})
          .add(&S::correlated, {.name = "correlated",
                                .doc = "pair the i-th time with the i-th lens point (interval "
                                       "methods' compromise: strobes)",
                                .invalidatesHistory = true})
          .add(&S::jitter, {.name = "jitter",
                            .doc = "jitter samples inside their strata",
                            .invalidatesHistory = true})
          .add(&S::filter, {.name = "filter",
                            .doc = "pixel reconstruction filter (box: the reference's pixel area)",
                            .choices = {"box", "blackman_harris"},
                            .invalidatesHistory = true})
          .add(&S::filterRadius, {.name = "filter_radius",
                                  .min = 0.5,
                                  .max = 4,
                                  .doc = "filter radius in pixels",
                                  .invalidatesHistory = true})
          .add(&S::shading,
               {.name = "shading",
                .doc = "whitted: ray-traced shadows, mirrors, glass; local: Blinn-Phong without "
                       "shadows",
                .choices = {"whitted", "local"},
                .invalidatesHistory = true})
          .add(&S::shutterTime,
               {.name = "shutter_time",
                .min = -1,
                .max = 1,
                .doc = "every pair at this shutter fraction (a sharp image; -1: the pairs' own "
                       "times)",
                .invalidatesHistory = true})
          .add(&S::shadingRate,
               {.name = "shading_rate",
                .doc = "sample: every sample shaded; pixel: once per pixel and surface seen "
                       "(MSAA-style)",
                .choices = {"sample", "pixel"},
                .invalidatesHistory = true})
          .add(&S::textureFootprint,
               {.name = "texture_footprint",
                .min = 0.0625,
                .max = 4,
                .doc = "scale of a sample's texture filter footprint (0.5 = mip bias -1, as "
                       "temporal AA uses: the frames together sample each pixel more finely)",
                .invalidatesHistory = true})
          .add(&S::viewJitter,
               {.name = "view_jitter",
                .doc = "shift the samples by the view's sub-pixel jitter (a sequence for temporal "
                       "AA)",
                .invalidatesHistory = true})
          .nest(&S::whitted, whittedTable());
  return table;
}

struct InterleavedPass::Frame {
  const InterleavedSettings& s;
  int n, k;
  std::vector<TimeLensPair> pairs;
  const TileSet& tiles;
  const TileShape& shape;
  std::vector<float> taus;  // each pair's shutter fraction (0 without time)
  const Scene& scene;
  ShadingContext shading;
  RayTracer* rt;  // Whitted shading
  WhittedSettings ws;
  const ShadowMaps* shadowMaps;
  ShadowTally* tally;
};

std::vector<CounterDesc> InterleavedPass::counters() const {
  const InterleavedCounters c(*this);
  std::vector<CounterDesc> all = whittedCounters(*this);
  all.insert(all.end(), {{c.passes(), "(time, lens) passes n of the tile pattern"},
                         {c.samplesPerPixel(), "samples per pixel k"},
                         {c.minSimilarTimeDistance(),
                          "smallest distance in pixels between samples of similar time"},
                         {c.footprintTimeDiscrepancy(),
                          "mean discrepancy of the times under a pixel's filter footprint"}});
  return all;
}

InterleavedPass::Pairs InterleavedPass::framePairs(const FrameContext& ctx) const {
  const InterleavedSettings& s = settings();
  const int n = s.samples, k = s.spp;
  const std::string problem = tileShapeProblem(n, k);
  if (!problem.empty())
    throw InputError("", "pass '" + type() + "' parameters 'samples' and 'spp'", problem);
  const PairMetric metric = s.mode == InterleavedSettings::Mode::Dof          ? PairMetric::Lens
                            : s.mode == InterleavedSettings::Mode::MotionBlur ? PairMetric::Time
                                                                              : PairMetric::Both;
  Pairs p;
  p.pairs = stratifiedTimeLensPairs(n, ctx.seed, s.correlated);
  p.tiles = &tileSetFor(
      n, k, s.scheme == SamplingScheme::RandomTiles ? TileKind::Random : TileKind::ColoredCorner,
      metric, p.pairs, ctx.seed);
  p.taus.resize(size_t(n));
  for (int j = 0; j < n; ++j)
    p.taus[size_t(j)] = !s.time()            ? 0.0f
                        : s.shutterTime >= 0 ? s.shutterTime
                                             : p.pairs[size_t(j)].tau;
  return p;
}

const SampleLayout& InterleavedPass::layoutFor(const FrameContext& ctx, const TileSet& tiles, int W,
                                               int H) {
  const InterleavedSettings& s = settings();
  Hasher key;
  key.pod(int(s.scheme)).pod(W).pod(H).pod(ctx.seed).pod(s.jitter).pod(&tiles);
  if (!layout_ || layoutKey_ != key.value()) {
    layout_ = std::make_unique<SampleLayout>(
        buildSampleLayout(s.scheme, tiles, W, H, ctx.seed, s.jitter));
    layoutKey_ = key.value();
    ++layoutVersion_;
  }
  return *layout_;
}

std::vector<Camera> InterleavedPass::pairCameras(const View& v, const Pairs& p) const {
  const InterleavedSettings& s = settings();
  std::vector<Camera> cams;
  cams.reserve(p.pairs.size());
  for (size_t j = 0; j < p.pairs.size(); ++j) {
    TimeLensPair pair = p.pairs[j];
    pair.tau = p.taus[j];
    cams.push_back(
        cameraForPair(v, pair, s.time(), s.lens(), s.viewJitter ? v.jitter : Vec2{0, 0}));
  }
  return cams;
}

void InterleavedPass::reportTiles(FrameContext& ctx, const TileSet& tiles) const {
  const InterleavedCounters c(*this);
  ctx.report(*this, c.passes(), double(settings().samples));
  ctx.report(*this, c.samplesPerPixel(), double(settings().spp));
  ctx.report(*this, c.minSimilarTimeDistance(), tiles.quality.minSimilarTimeDistance);
  ctx.report(*this, c.footprintTimeDiscrepancy(), tiles.quality.meanFootprintDiscrepancy);
}

void InterleavedPass::execute(FrameContext& ctx) {
  const InterleavedSettings& s = settings();
  Pairs p = framePairs(ctx);
  const bool whittedShading = s.shading == InterleavedSettings::Shading::Whitted;
  RayTracer* rt = whittedShading ? &ctx.rayTracer() : nullptr;
  RayTracer* counted = whittedShading || tracesPrimaryRays() ? &ctx.rayTracer() : nullptr;
  const uint64_t raysBefore = counted ? counted->raysTraced() : 0;
  ShadowTally shadowTally;
  Frame f{s,
          s.samples,
          s.spp,
          std::move(p.pairs),
          *p.tiles,
          p.tiles->shape,
          std::move(p.taus),
          *ctx.scene,
          ShadingContext::from(*ctx.scene),
          rt,
          s.whitted.settings(),
          rt ? shadowMapsFor(ctx, *this, s.whitted) : nullptr,
          &shadowTally};
  visMs_ = shadeMs_ = resolveMs_ = 0;
  for (const View& v : ctx.views) renderView(ctx, f, v);
  if (counted) ctx.passRays += double(counted->raysTraced() - raysBefore);
  if (rt) reportShadows(ctx, *this, sum(shadowTally), double(ctx.width) * double(ctx.height));
  ctx.passParts.push_back({"visibility", visMs_, 0});
  ctx.passParts.push_back({"shade", shadeMs_, 0});
  ctx.passParts.push_back({"resolve", resolveMs_, 0});
  reportTiles(ctx, f.tiles);
}

void InterleavedPass::renderView(FrameContext& ctx, const Frame& f, const View& v) {
  const InterleavedSettings& s = f.s;
  const SampleLayout& L = layoutFor(ctx, f.tiles, v.width(), v.height());
  const std::vector<Camera> cams = pairCameras(v, Pairs{f.pairs, &f.tiles, f.taus});

  // 0. Which samples are needed: those of pixels within the filter's reach of the mask.
  const Buffer* mask = ctx.optionalInput(*this, Slots::sampleMask);
  // Pixels whose samples the filter reaches: a sample lies inside its pixel, so a radius r
  // reaches ceil(r - 1/2) pixels out (the pixel box: the pixel's own samples).
  const int reach = int(std::ceil(s.filterRadius - 0.5f));
  std::vector<uint8_t> wanted;  // per pixel: resolved (mask > 0)
  if (mask) markActive(*mask, v, reach, wanted);
  const uint8_t* active = mask ? active_.data() : nullptr;

  // 1. Visibility of every sample.
  auto t0 = Clock::now();
  vis_.resize(L.stridesW(), L.stridesH());
  visibility(ctx, L, cams, f.taus, active, vis_);
  visMs_ += msSince(t0);

  // 2. Shading.
  auto t1 = Clock::now();
  shadeSamples(ctx, f, v, cams, active);
  shadeMs_ += msSince(t1);

  // 3. Resolve, and the buffers the post-process motion blur and the viewer read.
  auto t2 = Clock::now();
  resolve(f, v, ctx.output(*this, Slots::hdr), reach, mask ? &wanted : nullptr);
  writeMotion(ctx, f, v, cams, active, ctx.output(*this, Slots::velocity),
              ctx.output(*this, Slots::viewDepth), ctx.outputIfConsumed(*this, Slots::motion));
  writeViewerBuffers(ctx, Pairs{f.pairs, &f.tiles, f.taus}, v);
  resolveMs_ += msSince(t2);
}

void InterleavedPass::markActive(const Buffer& mask, const View& v, int reach,
                                 std::vector<uint8_t>& wanted) {
  const SampleLayout& L = *layout_;
  const TileShape& shape = L.shape;
  const int W = v.width(), H = v.height(), SW = L.stridesW();
  wanted.assign(size_t(W) * H, 0);
  std::vector<uint8_t> near(size_t(W) * H, 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      if (mask.at(x + v.x, y + v.y)[0] > 0) {
        wanted[size_t(y) * W + size_t(x)] = 1;
        for (int yy = std::max(0, y - reach); yy <= std::min(H - 1, y + reach); ++yy)
          for (int xx = std::max(0, x - reach); xx <= std::min(W - 1, x + reach); ++xx)
            near[size_t(yy) * W + size_t(xx)] = 1;
      }
  active_.assign(L.sampleCount(), 0);
  for (int y = 0; y < L.stridesH(); ++y)
    for (int x = 0; x < SW; ++x)
      active_[size_t(y) * size_t(SW) + size_t(x)] =
          near[size_t(y / shape.sy) * W + size_t(x / shape.sx)];
}

void InterleavedPass::findRepresentatives(const Frame& f, int W, int H) {
  // A pixel's samples that see the same triangle at the same pair (or the same time, when the
  // lens does not vary) take the colour of the first of them.
  const SampleLayout& L = *layout_;
  const TileShape& shape = f.shape;
  const int SW = L.stridesW();
  const bool lens = f.s.lens();
  rep_.resize(L.sampleCount());
  parallelTiles(W, H, [&](int x0, int y0, int x1, int y1) {
    for (int py = y0; py < y1; ++py)
      for (int px = x0; px < x1; ++px) {
        uint32_t ids[64];
        int m = 0;
        for (int sy = 0; sy < shape.sy; ++sy)
          for (int sx = 0; sx < shape.sx; ++sx) {
            const uint32_t id =
                uint32_t(size_t(py * shape.sy + sy) * size_t(SW) + size_t(px * shape.sx + sx));
            rep_[id] = id;
            for (int q = 0; q < m; ++q)
              if (vis_.object[ids[q]] == vis_.object[id] && vis_.prim[ids[q]] == vis_.prim[id] &&
                  (L.pair[ids[q]] == L.pair[id] ||
                   (!lens && f.taus[L.pair[ids[q]]] == f.taus[L.pair[id]]))) {
                rep_[id] = ids[q];
                break;
              }
            if (rep_[id] == id) ids[m++] = id;
          }
      }
  });
}

void InterleavedPass::shadeSamples(FrameContext& ctx, const Frame& f, const View& v,
                                   const std::vector<Camera>& cams, const uint8_t* active) {
  // Pass by pass (one time per pass), 8 samples at a time.
  const SampleLayout& L = *layout_;
  const Scene& scene = f.scene;
  colour_.resize(L.sampleCount());
  position_.resize(L.sampleCount());
  const float spread = ctx.pixelSpread(v) / std::sqrt(float(f.k)) * f.s.textureFootprint;
  const bool perPixel = f.s.shadingRate == InterleavedSettings::ShadingRate::Pixel;
  if (perPixel) findRepresentatives(f, v.width(), v.height());
  for (int j = 0; j < f.n; ++j) {
    const uint32_t b = L.passBegin(j), e = L.passEnd(j);
    const Camera& cam = cams[size_t(j)];
    const float tau = f.taus[size_t(j)];
    std::unique_ptr<Whitted> whitted;
    if (f.rt) {
      whitted = std::make_unique<Whitted>(Whitted(*f.rt, scene, f.shading, f.ws).atTime(tau));
      whitted->useShadowMaps(f.shadowMaps);
      whitted->countShadows(f.tally);
    }
    parallelBlocks(size_t(e - b), 256, [&](size_t s0, size_t s1) {
      SurfaceSample s[8];
      Vec3 d[8], out[8];
      uint32_t at[8];
      int m = 0;
      auto flush = [&] {
        if (m == 0) return;
        if (whitted) {
          whitted->shadePrimary8(s, d, m, out);
        } else {
          // Local shading: the same kernel as shadeBlinnPhong, 8 lanes at once.
          ShadeBatch batch;
          batch.count = m;
          for (int q = 0; q < m; ++q) batch.set(q, s[q], -d[q]);
          shadeBatch(batch, f.shading);
          for (int q = 0; q < m; ++q) out[q] = batch.result(q);
        }
        for (int q = 0; q < m; ++q) {
          colour_[at[q]] = out[q];
          position_[at[q]] = s[q].position;
        }
        m = 0;
      };
      for (size_t q = b + s0; q < b + s1; ++q) {
        const uint32_t id = L.ids[q];
        if ((active && !active[id]) || (perPixel && rep_[id] != id)) continue;
        Vec3 o, dir;
        cam.generateRay(L.pos[id].x, L.pos[id].y, o, dir);
        if (vis_.object[id] == kNoObject) {
          colour_[id] = scene.skyRadiance(dir);
          continue;
        }
        s[m] = resolveSurface(ctx.frame, int(vis_.object[id]), int(vis_.prim[id]), o, dir, tau,
                              nullptr, spread);
        d[m] = dir;
        at[m++] = id;
        if (m == 8) flush();
      }
      flush();
    });
  }
  if (perPixel)
    parallelRange(L.sampleCount(), [&](size_t b, size_t e) {
      for (size_t id = b; id < e; ++id)
        if (rep_[id] != id) colour_[id] = colour_[rep_[id]];
    });
}

void InterleavedPass::resolve(const Frame& f, const View& v, Buffer& hdr, int reach,
                              const std::vector<uint8_t>* wanted) const {
  // A separable box or Blackman-Harris weight of each sample's offset.
  const SampleLayout& L = *layout_;
  const TileShape& shape = f.shape;
  const int W = v.width(), H = v.height(), SW = L.stridesW();
  const float radius = f.s.filterRadius;
  const bool bh = f.s.filter == InterleavedSettings::Filter::BlackmanHarris;
  // The 1D weight tabulated over [0, radius] (the window's cosines once, not per sample).
  constexpr int kTable = 1024;
  std::vector<float> table(kTable + 2);
  for (int i = 0; i <= kTable + 1; ++i)
    table[size_t(i)] = i > kTable ? 0.0f : bh ? blackmanHarris(float(i) / kTable) : 1.0f;
  const float toTable = float(kTable) / radius;
  auto weight = [&](float d) {
    const float a = std::abs(d);
    return a > radius ? 0.0f : table[size_t(int(a * toTable + 0.5f))];
  };
  parallelTiles(W, H, [&](int x0, int y0, int x1, int y1) {
    for (int py = y0; py < y1; ++py)
      for (int px = x0; px < x1; ++px) {
        const float cx = float(px) + 0.5f, cy = float(py) + 0.5f;
        if (wanted && !(*wanted)[size_t(py) * W + size_t(px)]) {
          float* h = hdr.at(px + v.x, py + v.y);
          h[0] = h[1] = h[2] = 0.0f;
          continue;
        }
        Vec3 sum{0.0f};
        float wsum = 0;
        for (int qy = std::max(0, py - reach); qy <= std::min(H - 1, py + reach); ++qy)
          for (int qx = std::max(0, px - reach); qx <= std::min(W - 1, px + reach); ++qx)
            for (int sy = 0; sy < shape.sy; ++sy)
              for (int sx = 0; sx < shape.sx; ++sx) {
                const size_t id =
                    size_t(qy * shape.sy + sy) * size_t(SW) + size_t(qx * shape.sx + sx);
                const float w = weight(L.pos[id].x - cx) * weight(L.pos[id].y - cy);
                if (w <= 0) continue;
                sum = sum + colour_[id] * w;
                wsum += w;
              }
        float* h = hdr.at(px + v.x, py + v.y);
        if (wsum > 1e-12f) sum = sum * (1.0f / wsum);
        h[0] = sum.x;
        h[1] = sum.y;
        h[2] = sum.z;
      }
  });
}

InterleavedPass::MotionCarry InterleavedPass::motionCarry(const FrameContext& ctx,
                                                          const std::vector<float>& taus,
                                                          const View& v, bool motion) const {
  // Per pair and animated object: world at open (and close) after world at the pair's time
  // undone.
  // Motion (frame to frame, for temporal AA): the same point at the pair's shutter fraction of
  // the previous frame, seen by the previous camera moved as far into its shutter (its
  // displacement over the shutter taken as this frame's).
  const Scene& scene = *ctx.scene;
  const size_t n = taus.size();
  const float t0s = ctx.frame.time, t1s = ctx.frame.shutterClose, tPrev = ctx.frame.prevTime;
  MotionCarry mc;
  mc.carry.resize(n);
  mc.carryPrev.resize(n);
  for (size_t j = 0; j < n; ++j) {
    const float into = (t1s - t0s) * taus[j];
    mc.carry[j].resize(scene.objects.size());
    mc.carryPrev[j].resize(scene.objects.size());
    for (size_t o = 0; o < scene.objects.size(); ++o) {
      const Object& obj = scene.objects[o];
      if (!obj.animated()) continue;
      const Mat4 undo = obj.worldMatrix(t0s + into).inverse();
      mc.carry[j][o] = {obj.worldMatrix(t0s) * undo, obj.worldMatrix(t1s) * undo};
      mc.carryPrev[j][o] = obj.worldMatrix(tPrev + into) * undo;
    }
    if (motion) {
      const float tau = settings().time() ? taus[j] : 0.0f;
      auto intoShutter = [&](CameraDesc d) {
        d.position = d.position + (v.shutterCamera.desc.position - v.camera.desc.position) * tau;
        d.lookAt = d.lookAt + (v.shutterCamera.desc.lookAt - v.camera.desc.lookAt) * tau;
        return Camera::make(d, v.width(), v.height());
      };
      mc.nowCams.push_back(intoShutter(v.camera.desc));
      mc.prevCams.push_back(intoShutter(v.prevCamera.desc));
    }
  }
  return mc;
}

void InterleavedPass::writeMotion(FrameContext& ctx, const Frame& f, const View& v,
                                  const std::vector<Camera>& cams, const uint8_t* active,
                                  Buffer& velocityOut, Buffer& depthOut, Buffer* motionOut) const {
  const SampleLayout& L = *layout_;
  const TileShape& shape = f.shape;
  const Scene& scene = f.scene;
  const int W = v.width(), H = v.height(), SW = L.stridesW();
  // Velocity and depth of each pixel's first sample, for the post-process motion blur: the
  // surface point carried rigidly with its object from the sample's time to shutter open and
  // close, projected through the cameras at open and close.
  const MotionCarry mc = motionCarry(ctx, f.taus, v, motionOut != nullptr);
  const auto& carry = mc.carry;
  const auto& carryPrev = mc.carryPrev;
  const auto& nowCams = mc.nowCams;
  const auto& prevCams = mc.prevCams;
  parallelTiles(W, H, [&](int x0, int y0, int x1, int y1) {
    for (int py = y0; py < y1; ++py)
      for (int px = x0; px < x1; ++px) {
        float* vel = velocityOut.at(px + v.x, py + v.y);
        float* dep = depthOut.at(px + v.x, py + v.y);
        float* mot = motionOut ? motionOut->at(px + v.x, py + v.y) : nullptr;
        const size_t id = size_t(py * shape.sy) * size_t(SW) + size_t(px * shape.sx);
        vel[0] = vel[1] = 0.0f;
        dep[0] = 1e30f;
        if (mot) mot[0] = mot[1] = 0.0f;
        if (active && !active[id]) continue;
        const int j = L.pair[id];
        Vec3 pOpen, pClose, pNow, pPrev;
        float wPoint = 1.0f;
        if (vis_.object[id] == kNoObject) {
          Vec3 o;
          cams[size_t(j)].generateRay(L.pos[id].x, L.pos[id].y, o, pOpen);
          pClose = pOpen;  // a direction: only the camera's rotation moves it
          pNow = pPrev = pOpen;
          wPoint = 0.0f;
        } else {
          const Vec3 p = position_[id];
          const size_t obj = vis_.object[id];
          pNow = p;
          if (scene.objects[obj].animated()) {
            pOpen = carry[size_t(j)][obj].first.transformPoint(p);
            pClose = carry[size_t(j)][obj].second.transformPoint(p);
            pPrev = carryPrev[size_t(j)][obj].transformPoint(p);
          } else {
            pOpen = pClose = pPrev = p;
          }
          dep[0] = dot(p - cams[size_t(j)].eye, cams[size_t(j)].forward);
        }
        auto toPixel = [&](const Camera& c, Vec3 q, Vec2& out) {
          const Vec4 h = c.viewProjUnjittered * Vec4(q, wPoint);
          if (h.w <= 1e-8f) return false;
          out = {(h.x / h.w * 0.5f + 0.5f) * float(W), (0.5f - h.y / h.w * 0.5f) * float(H)};
          return true;
        };
        Vec2 a, b;
        if (toPixel(v.camera, pOpen, a) && toPixel(v.shutterCamera, pClose, b)) {
          vel[0] = b.x - a.x;
          vel[1] = b.y - a.y;
        }
        if (mot && toPixel(nowCams[size_t(j)], pNow, a) && toPixel(prevCams[size_t(j)], pPrev, b)) {
          mot[0] = a.x - b.x;
          mot[1] = a.y - b.y;
        }
      }
  });
}

void InterleavedPass::writeViewerBuffers(FrameContext& ctx, const Pairs& f, const View& v) {
  const TileShape& shape = f.tiles->shape;
  Buffer* samplesOut =
      ctx.isConsumed(*this, Slots::sampleTimeLens)
          ? &ctx.output(*this, Slots::sampleTimeLens, ctx.width * shape.sx, ctx.height * shape.sy)
          : nullptr;
  Buffer* layoutOut = ctx.outputIfConsumed(*this, Slots::tileLayout);
  const SampleLayout& L = *layout_;
  const int H = v.height(), W = v.width(), SW = L.stridesW();
  // For the viewer: each sample's time and lens coordinates, each pixel's tile prototype.
  if (samplesOut)
    parallelRange(
        size_t(L.stridesH()),
        [&](size_t y0, size_t y1) {
          for (size_t y = y0; y < y1; ++y)
            for (int x = 0; x < SW; ++x) {
              const int j = L.pair[y * size_t(SW) + size_t(x)];
              float* o = samplesOut->at(x + v.x * shape.sx, int(y) + v.y * shape.sy);
              o[SampleChannels::kTime] = f.taus[size_t(j)];
              o[SampleChannels::kLensU] = f.pairs[size_t(j)].u1;
              o[SampleChannels::kLensV] = f.pairs[size_t(j)].u2;
            }
        },
        16);
  const bool tiled = settings().scheme >= SamplingScheme::RandomTiles;
  if (layoutOut)
    parallelRange(
        size_t(H),
        [&](size_t y0, size_t y1) {
          for (size_t y = y0; y < y1; ++y)
            for (int x = 0; x < W; ++x)
              layoutOut->at(x + v.x, int(y) + v.y)[0] =
                  tiled ? float(f.tiles->prototypeAt(x / shape.tw, int(y) / shape.th)) : -1.0f;
        },
        16);
}

}  // namespace tandem
