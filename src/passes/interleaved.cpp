#include "passes/interleaved.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>

#include "core/hash.h"
#include "core/parallel.h"
#include "passes/whitted_settings.h"
#include "pipeline/frame_context.h"
#include "rt/reference_render.h"
#include "rt/whitted.h"
#include "shading/blinn_phong.h"
#include "shading/shade_batch.h"
#include "shading/surface_resolve.h"

namespace tandem {

Camera cameraForPair(const View& v, const TimeLensPair& p, bool time, bool lens, Vec2 jitter) {
  const Camera atTau = time ? cameraAtShutter(v.camera, v.shutterCamera, p.tau) : v.camera;
  const Vec2 lensPoint = lens ? atTau.lensPoint(p.u1, p.u2) : Vec2{0, 0};
  return Camera::make(atTau.desc, v.width(), v.height(), jitter, lensPoint);
}

float blackmanHarris(float t) {
  // The 4-term window over [-1, 1] (Harris 1978), centred: x in [0, 1] maps to 0.5 + t / 2.
  if (t >= 1.0f) return 0.0f;
  const float x = kPi * (1.0f + t);  // 2 pi (0.5 + t / 2)
  return 0.35875f - 0.48829f * std::cos(x) + 0.14128f * std::cos(2 * x) -
         0.01168f * std::cos(3 * x);
}

std::vector<ParamDesc> InterleavedPass::params() const {
  std::vector<ParamDesc> p = {
      {"samples", ParamType::Int, 16, 1, 4096, "N: (time, lens) pairs in T (passes)", {}, true},
      {"spp", ParamType::Int, 4, 1, 64, "k: samples per pixel (N must be a multiple)", {}, true},
      {"scheme",
       ParamType::Enum,
       3,
       0,
       3,
       "how samples take pairs of T",
       {"independent", "stratified", "random_tiles", "colored_corner"},
       true},
      {"mode",
       ParamType::Enum,
       2,
       0,
       2,
       "what the pairs vary",
       {"dof", "motion_blur", "both"},
       true},
      {"correlated",
       ParamType::Bool,
       0,
       0,
       1,
       "pair the i-th time with the i-th lens point (interval methods' compromise: strobes)",
       {},
       true},
      {"jitter", ParamType::Bool, 1, 0, 1, "jitter samples inside their strata", {}, true},
      {"filter",
       ParamType::Enum,
       0,
       0,
       1,
       "pixel reconstruction filter (box: the reference's pixel area)",
       {"box", "blackman_harris"},
       true},
      {"filter_radius", ParamType::Float, 0.5, 0.5, 4, "filter radius in pixels", {}, true},
      {"shading",
       ParamType::Enum,
       0,
       0,
       1,
       "whitted: ray-traced shadows, mirrors, glass; local: Blinn-Phong without shadows",
       {"whitted", "local"},
       true},
      {"shutter_time",
       ParamType::Float,
       -1,
       -1,
       1,
       "every pair at this shutter fraction (a sharp image; -1: the pairs' own times)",
       {},
       true},
      {"shading_rate",
       ParamType::Enum,
       0,
       0,
       1,
       "sample: every sample shaded; pixel: once per pixel and surface seen (MSAA-style)",
       {"sample", "pixel"},
       true},
      {"texture_footprint",
       ParamType::Float,
       1,
       0.0625,
       4,
       "scale of a sample's texture filter footprint (0.5 = mip bias -1, as temporal AA uses: "
       "the frames together sample each pixel more finely)",
       {},
       true},
      {"view_jitter",
       ParamType::Bool,
       0,
       0,
       1,
       "shift the samples by the view's sub-pixel jitter (a sequence for temporal AA)",
       {},
       true}};
  for (const ParamDesc& d : whittedParams()) p.push_back(d);
  return p;
}

void InterleavedPass::execute(FrameContext& ctx) {
  const int n = int(param("samples")), k = int(param("spp")), mode = int(param("mode"));
  const std::string problem = tileShapeProblem(n, k);
  if (!problem.empty())
    throw InputError("", "pass '" + type() + "' parameters 'samples' and 'spp'", problem);
  const bool lens = mode != 1, time = mode != 0;
  const auto scheme = SamplingScheme(int(param("scheme")));
  const PairMetric metric = mode == 0   ? PairMetric::Lens
                            : mode == 1 ? PairMetric::Time
                                        : PairMetric::Both;
  const std::vector<TimeLensPair> pairs =
      stratifiedTimeLensPairs(n, ctx.seed, param("correlated") != 0);
  const TileSet& tiles = tileSetFor(
      n, k, scheme == SamplingScheme::RandomTiles ? TileKind::Random : TileKind::ColoredCorner,
      metric, pairs, ctx.seed);
  const TileShape& shape = tiles.shape;
  Buffer& hdr = ctx.output(*this, "hdr");
  // The viewer's buffers, only when something reads them.
  Buffer* samplesOut =
      ctx.isConsumed(*this, "sample_time_lens")
          ? &ctx.output(*this, "sample_time_lens", ctx.width * shape.sx, ctx.height * shape.sy)
          : nullptr;
  Buffer* layoutOut = ctx.outputIfConsumed(*this, "tile_layout");
  Buffer& velocityOut = ctx.output(*this, "velocity");
  Buffer& depthOut = ctx.output(*this, "view_depth");
  Buffer* motionOut = ctx.outputIfConsumed(*this, "motion");
  const bool viewJitter = param("view_jitter") != 0;
  const Scene& scene = *ctx.scene;
  const ShadingContext shading = ShadingContext::from(scene);
  const bool whittedShading = param("shading") == 0;
  RayTracer* rt = whittedShading ? &ctx.rayTracer() : nullptr;
  RayTracer* counted = whittedShading || tracesPrimaryRays() ? &ctx.rayTracer() : nullptr;
  const uint64_t raysBefore = counted ? counted->raysTraced() : 0;
  const WhittedSettings ws = whittedSettings(*this);
  const ShadowMaps* shadowMaps = rt ? shadowMapsFor(ctx, *this) : nullptr;
  ShadowTally shadowTally;
  std::vector<float> taus(static_cast<size_t>(n));
  const float fixedTau = float(param("shutter_time"));
  for (int j = 0; j < n; ++j)
    taus[size_t(j)] = !time ? 0.0f : fixedTau >= 0 ? fixedTau : pairs[size_t(j)].tau;
  double visMs = 0, shadeMs = 0, resolveMs = 0;

  for (const View& v : ctx.views) {
    const int W = v.width(), H = v.height();
    Hasher key;
    key.pod(int(scheme)).pod(W).pod(H).pod(ctx.seed).pod(param("jitter")).pod(&tiles);
    if (!layout_ || layoutKey_ != key.value()) {
      layout_ = std::make_unique<SampleLayout>(
          buildSampleLayout(scheme, tiles, W, H, ctx.seed, param("jitter") != 0));
      layoutKey_ = key.value();
    }
    const SampleLayout& L = *layout_;
    std::vector<Camera> cams;
    cams.reserve(size_t(n));
    for (int j = 0; j < n; ++j) {
      TimeLensPair p = pairs[size_t(j)];
      p.tau = taus[size_t(j)];
      cams.push_back(cameraForPair(v, p, time, lens, viewJitter ? v.camera.jitter : Vec2{0, 0}));
    }

    // 0. Which samples are needed: those of pixels within the filter's reach of the mask.
    const Buffer* mask = ctx.optionalInput(*this, "sample_mask");
    // Pixels whose samples the filter reaches: a sample lies inside its pixel, so a radius r
    // reaches ceil(r - 1/2) pixels out (the pixel box: the pixel's own samples).
    const int reach = int(std::ceil(float(param("filter_radius")) - 0.5f));
    const int SW = L.stridesW();
    std::vector<uint8_t> wanted;  // per pixel: resolved (mask > 0)
    if (mask) {
      wanted.assign(size_t(W) * H, 0);
      std::vector<uint8_t> near(size_t(W) * H, 0);
      for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
          if (mask->at(x + v.x, y + v.y)[0] > 0) {
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
    const uint8_t* active = mask ? active_.data() : nullptr;

    // 1. Visibility of every sample.
    auto t0 = Clock::now();
    vis_.resize(L.stridesW(), L.stridesH());
    visibility(ctx, L, cams, taus, active, vis_);
    visMs += msSince(t0);

    // 2. Shading, pass by pass (one time per pass), 8 samples at a time.
    auto t1 = Clock::now();
    colour_.resize(L.sampleCount());
    position_.resize(L.sampleCount());
    const float spread =
        ctx.pixelSpread(v) / std::sqrt(float(k)) * float(param("texture_footprint"));
    // Shading per pixel (MSAA-style): a pixel's samples that see the same triangle at the same
    // pair (or the same time, when the lens does not vary) take the colour of the first of them.
    const bool perPixel = param("shading_rate") == 1;
    if (perPixel) {
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
                  if (vis_.object[ids[q]] == vis_.object[id] &&
                      vis_.prim[ids[q]] == vis_.prim[id] &&
                      (L.pair[ids[q]] == L.pair[id] ||
                       (!lens && taus[L.pair[ids[q]]] == taus[L.pair[id]]))) {
                    rep_[id] = ids[q];
                    break;
                  }
                if (rep_[id] == id) ids[m++] = id;
              }
          }
      });
    }
    for (int j = 0; j < n; ++j) {
      const uint32_t b = L.passBegin(j), e = L.passEnd(j);
      const Camera& cam = cams[size_t(j)];
      const float tau = taus[size_t(j)];
      std::unique_ptr<Whitted> whitted;
      if (rt) {
        whitted = std::make_unique<Whitted>(Whitted(*rt, scene, shading, ws).atTime(tau));
        whitted->useShadowMaps(shadowMaps);
        whitted->countShadows(&shadowTally);
      }
      parallelRange(
          size_t(e - b),
          [&](size_t s0, size_t s1) {
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
                shadeBatch(batch, shading);
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
              s[m] = resolveSurface(ctx.frame, int(vis_.object[id]), int(vis_.prim[id]), o, dir,
                                    tau, nullptr, spread);
              d[m] = dir;
              at[m++] = id;
              if (m == 8) flush();
            }
            flush();
          },
          256);
    }
    if (perPixel)
      parallelRange(L.sampleCount(), [&](size_t b, size_t e) {
        for (size_t id = b; id < e; ++id)
          if (rep_[id] != id) colour_[id] = colour_[rep_[id]];
      });
    shadeMs += msSince(t1);

    // 3. Resolve to pixels: a separable box or Blackman-Harris weight of each sample's offset.
    auto t2 = Clock::now();
    const float radius = float(param("filter_radius"));
    const bool bh = param("filter") == 1;
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
          if (mask && !wanted[size_t(py) * W + size_t(px)]) {
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
    // Velocity and depth of each pixel's first sample, for the post-process motion blur: the
    // surface point carried rigidly with its object from the sample's time to shutter open and
    // close, projected through the cameras at open and close.
    const float t0s = ctx.frame.time, t1s = ctx.frame.shutterClose;
    // Per pair and animated object: world at open (and close) after world at the pair's time
    // undone.
    // Motion (frame to frame, for temporal AA): the same point at the pair's shutter fraction of
    // the previous frame, seen by the previous camera moved as far into its shutter (its
    // displacement over the shutter taken as this frame's).
    const float tPrev = ctx.frame.prevTime;
    std::vector<std::vector<std::pair<Mat4, Mat4>>> carry(static_cast<size_t>(n));
    std::vector<std::vector<Mat4>> carryPrev(static_cast<size_t>(n));
    std::vector<Camera> nowCams, prevCams;
    for (int j = 0; j < n; ++j) {
      const float into = (t1s - t0s) * taus[size_t(j)];
      carry[size_t(j)].resize(scene.objects.size());
      carryPrev[size_t(j)].resize(scene.objects.size());
      for (size_t o = 0; o < scene.objects.size(); ++o) {
        const Object& obj = scene.objects[o];
        if (!obj.animated()) continue;
        const Mat4 undo = obj.worldMatrix(t0s + into).inverse();
        carry[size_t(j)][o] = {obj.worldMatrix(t0s) * undo, obj.worldMatrix(t1s) * undo};
        carryPrev[size_t(j)][o] = obj.worldMatrix(tPrev + into) * undo;
      }
      if (motionOut) {
        const float tau = time ? taus[size_t(j)] : 0.0f;
        auto intoShutter = [&](CameraDesc d) {
          d.position = d.position + (v.shutterCamera.desc.position - v.camera.desc.position) * tau;
          d.lookAt = d.lookAt + (v.shutterCamera.desc.lookAt - v.camera.desc.lookAt) * tau;
          return Camera::make(d, W, H);
        };
        nowCams.push_back(intoShutter(v.camera.desc));
        prevCams.push_back(intoShutter(v.prevCamera.desc));
      }
    }
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
          if (mot && toPixel(nowCams[size_t(j)], pNow, a) &&
              toPixel(prevCams[size_t(j)], pPrev, b)) {
            mot[0] = a.x - b.x;
            mot[1] = a.y - b.y;
          }
        }
    });

    // For the viewer: each sample's time and lens coordinates, each pixel's tile prototype.
    if (samplesOut)
      parallelRange(
          size_t(L.stridesH()),
          [&](size_t y0, size_t y1) {
            for (size_t y = y0; y < y1; ++y)
              for (int x = 0; x < SW; ++x) {
                const int j = L.pair[y * size_t(SW) + size_t(x)];
                float* o = samplesOut->at(x + v.x * shape.sx, int(y) + v.y * shape.sy);
                o[0] = taus[size_t(j)];
                o[1] = pairs[size_t(j)].u1;
                o[2] = pairs[size_t(j)].u2;
              }
          },
          16);
    const bool tiled = scheme >= SamplingScheme::RandomTiles;
    if (layoutOut)
      parallelRange(
          size_t(H),
          [&](size_t y0, size_t y1) {
            for (size_t y = y0; y < y1; ++y)
              for (int x = 0; x < W; ++x)
                layoutOut->at(x + v.x, int(y) + v.y)[0] =
                    tiled ? float(tiles.prototypeAt(x / shape.tw, int(y) / shape.th)) : -1.0f;
          },
          16);
    resolveMs += msSince(t2);
  }
  if (counted) ctx.passRays += double(counted->raysTraced() - raysBefore);
  if (rt) reportShadows(ctx, *this, sum(shadowTally), double(ctx.width) * double(ctx.height));
  ctx.passParts.push_back({"visibility", visMs, 0});
  ctx.passParts.push_back({"shade", shadeMs, 0});
  ctx.passParts.push_back({"resolve", resolveMs, 0});
  ctx.counters[type() + "/passes"] = double(n);
  ctx.counters[type() + "/samples_per_pixel"] = double(k);
  ctx.counters[type() + "/min_similar_time_distance_px"] = tiles.quality.minSimilarTimeDistance;
  ctx.counters[type() + "/footprint_time_discrepancy"] = tiles.quality.meanFootprintDiscrepancy;
}

void InterleavedRasterPass::visibility(FrameContext& ctx, const SampleLayout& layout,
                                       const std::vector<Camera>& cams,
                                       const std::vector<float>& taus, const uint8_t* active,
                                       VisibilityBuffer& vis) {
  // A masked pass draws only the cells (tiles) that hold a needed sample.
  const TileShape& shape = layout.shape;
  if (active) {
    cellActive_.assign(size_t(layout.cells()), 0);
    const int SW = layout.stridesW(), cellSW = shape.tw * shape.sx, cellSH = shape.th * shape.sy;
    for (int y = 0; y < layout.stridesH(); ++y)
      for (int x = 0; x < SW; ++x)
        if (active[size_t(y) * size_t(SW) + size_t(x)])
          cellActive_[size_t(y / cellSH) * size_t(layout.cellsX) + size_t(x / cellSW)] = 1;
  }
  auto masked = [&](Rasterizer::SampleSet set) {
    set.cellActive = active ? cellActive_.data() : nullptr;
    return set;
  };
  // Every sample: a pass costs its triangles' setup, not its samples.
  // When no pair moves the camera (no lens, no camera motion in the shutter), geometry that
  // stands still looks the same at every pair: it is rasterized once into every sample, and
  // only the moving objects once per pair, over it.
  const bool moving = ctx.frame.motionBlur();
  bool sameView = true;
  for (const Camera& c : cams) sameView = sameView && sameMatrix(c.viewProj, cams.front().viewProj);
  std::vector<uint8_t> movers(ctx.frame.objects.size(), 0), still(movers.size(), 0);
  size_t moverCount = 0;
  for (size_t o = 0; o < movers.size(); ++o) {
    movers[o] = !ctx.frame.objects[o].stepPositions.empty();
    still[o] = !movers[o];
    moverCount += movers[o];
  }
  const bool shareStatic = sameView && cams.size() > 1;
  double setUp = 0, setUpMax = 0, setUpMin = 1e300, shared = 0;
  if (shareStatic) {
    RasterStats stats;
    rasterizer_.renderSamples(ctx.frame, cams.front(), masked(layout.allSamples()), vis,
                              Rasterizer::Subset{&still, false}, &stats,
                              moving ? taus.front() : -1.0f);
    shared = double(stats.trianglesBinned);
  }
  for (size_t j = 0; j < cams.size(); ++j) {
    if (shareStatic && moverCount == 0) break;
    RasterStats stats;
    const Rasterizer::Subset subset =
        shareStatic ? Rasterizer::Subset{&movers, true} : Rasterizer::Subset{};
    rasterizer_.renderSamples(ctx.frame, cams[j], masked(layout.passSamples(int(j))), vis, subset,
                              &stats, moving ? taus[j] : -1.0f);
    setUp += double(stats.trianglesBinned);
    setUpMax = std::max(setUpMax, double(stats.trianglesBinned));
    setUpMin = std::min(setUpMin, double(stats.trianglesBinned));
  }
  ctx.counters["interleaved_raster/triangles_set_up_per_pass"] = setUp / double(cams.size());
  ctx.counters["interleaved_raster/triangles_set_up_max"] = setUpMax;
  ctx.counters["interleaved_raster/triangles_set_up_min"] = std::min(setUpMin, setUpMax);
  ctx.counters["interleaved_raster/static_triangles_set_up_once"] = shared;
}

void InterleavedRTPass::visibility(FrameContext& ctx, const SampleLayout& layout,
                                   const std::vector<Camera>& cams, const std::vector<float>& taus,
                                   const uint8_t* active, VisibilityBuffer& vis) {
  RayTracer& rt = ctx.rayTracer();
  for (size_t j = 0; j < cams.size(); ++j) {
    const uint32_t b = layout.passBegin(int(j)), e = layout.passEnd(int(j));
    const Camera& cam = cams[j];
    const float tau = taus[j];
    parallelRange(
        size_t(e - b),
        [&](size_t s0, size_t s1) {
          Ray rays[8];
          Hit hits[8];
          uint32_t at[8];
          int m = 0;
          auto flush = [&] {
            rt.intersect8(rays, m, hits, /*cullBackfaces=*/true);
            for (int q = 0; q < m; ++q) {
              vis.object[at[q]] = hits[q].valid() ? uint32_t(hits[q].object) : kNoObject;
              vis.prim[at[q]] = hits[q].valid() ? uint32_t(hits[q].prim) : 0u;
            }
            m = 0;
          };
          for (size_t q = b + s0; q < b + s1; ++q) {
            const uint32_t id = layout.ids[q];
            if (active && !active[id]) continue;
            Ray& r = rays[m];
            cam.generateRay(layout.pos[id].x, layout.pos[id].y, r.origin, r.dir);
            r.time = tau;
            at[m++] = id;
            if (m == 8) flush();
          }
          if (m > 0) flush();
        },
        256);
  }
}

}  // namespace tandem
