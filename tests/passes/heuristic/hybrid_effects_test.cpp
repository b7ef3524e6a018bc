// The hybrid pipeline's effect mask end to end: per-effect blending, the RT pass's per-object
// measurements, the ms-budget calibration and the equivalences between modes.
#include <gtest/gtest.h>

#include <any>
#include <mutex>
#include <random>

#include <tbb/task_arena.h>

#include <hwy/targets.h>
#include "eval/metrics/metrics.h"
#include "passes/heuristic/blend.h"

#include "passes/heuristic/heuristic.h"
#include "passes/heuristic/ranked_tiles.h"
#include "passes/heuristic/reflection_probes.h"
#include "pipeline/frame_context.h"
#include "raster/shadow_maps.h"
#include "rt/ray_tracer.h"
#include "rt/whitted.h"
#include "scene/builtin_scenes.h"
#include "test_util.h"

using namespace tandem;

namespace {

std::unique_ptr<Renderer> makeRenderer(const Scene& s, const std::string& pipeline,
                                       const std::vector<std::string>& params, int w, int h) {
  Pipeline p = Pipeline::load(pipeline);
  for (const std::string& a : params) p.setParam(a, "test");
  return std::make_unique<Renderer>(s, std::move(p), RenderSettings{.width = w, .height = h});
}

const HeuristicPass& heuristicOf(Renderer& r) {
  for (const auto& p : r.pipeline().passes)
    if (auto* h = dynamic_cast<const HeuristicPass*>(p.get())) return *h;
  throw std::runtime_error("no heuristic pass");
}

bool sameBuffer(const Buffer& a, const Buffer& b) {
  return a.sameShape(b) && a.data == b.data;
}

}  // namespace

// Blend with a per-effect mask: an effect not traced counts as absent (eq. 4-6 with O = 0).
TEST(HybridEffects, BlendHonoursEachMaskChannel) {
  FrameContext ctx;
  ctx.width = 4;
  ctx.height = 1;
  const Vec3 L(0.6f, 0.5f, 0.4f), S(0.5f, 0.5f, 0.5f), M(0.9f, 0.1f, 0.1f), R(0.1f, 0.9f, 0.1f);
  const float om = 0.3f, opacity = 0.25f;
  const float masks[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1}};
  auto make = [&](const char* name) -> Buffer& {
    Buffer& b = ctx.buffers[name];
    if (b.width == 0) b = Buffer(4, 1, 3);
    return b;
  };
  for (auto [name, c] : {std::pair{"hdr", L}, {"shadow", S}, {"reflection", M}, {"refraction", R}})
    for (int x = 0; x < 4; ++x) make(name).setRgb(x, 0, c);
  for (int x = 0; x < 4; ++x) {
    make("optical").setRgb(x, 0, {om, 1.5f, opacity});
    float* m = make("heuristic_mask").at(x, 0);
    for (int k = 0; k < 3; ++k) m[k] = masks[x][k];
  }
  BlendPass blend;
  blend.execute(ctx);
  const Buffer& out = ctx.input("composite");
  const Vec3 C = L - (Vec3(1.0f) - S);  // eq. 4
  // Pixel 2 has no shadow traced: its shadow buffer value is ignored, not subtracted.
  const Vec3 expect[4] = {L, C, combineEffects(om, 0, M, R, L),
                          combineEffects(om, 1 - opacity, M, R, C)};
  for (int x = 0; x < 4; ++x)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(out.at(x, 0)[k], expect[x][k], 1e-6f) << x;
}

// The RT pass measures exactly the pixels the mask gave it, per object and effect, and at most
// one shadow ray per light per pixel (every shadow traced: classified shadows trace fewer).
TEST(HybridEffects, RtStatsCountMaskedPixels) {
  Scene s = makeSpheresScene();
  auto r = makeRenderer(s, "hybrid-all", {"rt_secondary.shadows=rays"}, 96, 54);
  r->renderFrame(0, s.camera);
  const FrameContext& ctx = r->context();
  const RtStats& stats = std::any_cast<const RtStats&>(ctx.input("rt_stats").record);
  ASSERT_EQ(stats.pixels.size(), s.objects.size());
  std::vector<uint32_t> pixels = countObjectPixels(ctx.input("object_id"), s.objects.size());
  uint64_t totalShadowRays = 0, totalPixels = 0;
  for (size_t o = 0; o < s.objects.size(); ++o) {
    const Material& m = s.materials[s.objects[o].material];
    EXPECT_EQ(stats.pixels[o][kShadow], pixels[o]) << o;
    EXPECT_EQ(stats.pixels[o][kReflection], m.reflectivity > 0 ? pixels[o] : 0u) << o;
    EXPECT_EQ(stats.pixels[o][kRefraction], m.opacity < 1 ? pixels[o] : 0u) << o;
    EXPECT_LE(stats.rays[o][kShadow], uint64_t(pixels[o]) * s.lights.size()) << o;
    totalShadowRays += stats.rays[o][kShadow];
    totalPixels += pixels[o];
  }
  EXPECT_GT(totalShadowRays, totalPixels);  // most pixels face at least one light
  EXPECT_GT(stats.ms, 0.0);
}

// The heuristic's request and rt_secondary's stats are records: the stats of the frame's pixels,
// and the request asks for per-effect timing only with a ms budget.
TEST(HybridEffects, FeedbackIsTypedRecords) {
  const Scene s = makeSpheresScene();
  auto r = test::renderOnce(s, "hybrid-budget", 48, 27, s.camera);
  const FrameContext& ctx = r->context();
  const RtRequest* request = std::any_cast<RtRequest>(&ctx.input("rt_request").record);
  ASSERT_NE(request, nullptr);
  EXPECT_TRUE(request->timeEffects);
  EXPECT_GT(request->deadlineMs, 0.0);
  const RtStats* stats = std::any_cast<RtStats>(&ctx.input("rt_stats").record);
  ASSERT_NE(stats, nullptr);
  EXPECT_EQ(stats->pixels.size(), s.objects.size());
  EXPECT_TRUE(stats->timeEffects);
  auto plain = test::renderOnce(s, "hybrid-all", 48, 27, s.camera);
  const RtRequest* none = std::any_cast<RtRequest>(&plain->context().input("rt_request").record);
  ASSERT_NE(none, nullptr);
  EXPECT_FALSE(none->timeEffects);
  EXPECT_EQ(none->deadlineMs, 0.0);
}

// Per-effect selection with everything selected (shadows with their objects, rt_secondary's
// recursion as deep as the pass's default) is the paper's hybrid-all, pixel for pixel; a
// zero budget with the fallbacks off (the paper's rule) ray traces nothing and leaves the
// deferred image.
TEST(HybridEffects, ModesAgreeAtTheExtremes) {
  Scene s = makeSpheresScene();
  auto all = test::renderOnce(s, "hybrid-all", 96, 54, s.camera);
  auto perEffect = makeRenderer(
      s, "hybrid-heuristic",
      {"heuristic.select_all=1", "heuristic.per_effect=1", "deferred_shading.shadows=off",
       "heuristic.shadows=budget", "rt_secondary.max_depth=10"},
      96, 54);
  perEffect->renderFrame(0, s.camera);
  EXPECT_TRUE(sameBuffer(all->output(), perEffect->output()));
  auto none =
      makeRenderer(s, "hybrid-heuristic",
                   {"heuristic.budget=0", "deferred_shading.shadows=off",
                    "heuristic.shadows=budget", "ss_fallback.mode=off", "ss_fallback.shadows=off"},
                   96, 54);
  none->renderFrame(0, s.camera);
  auto deferred = test::renderOnce(s, "deferred", 96, 54, s.camera);
  EXPECT_TRUE(sameBuffer(none->output(), deferred->output()));
  EXPECT_TRUE(heuristicOf(*none).lastSelection().empty());
}

// The ms budget: costs are predicted CPU ms (visible pixels x the CPU ms per pixel the RT pass
// measured for that object and effect), and T = budget_ms x (predicted ms selected last frame /
// RT wall ms last frame). The measured wall time is set by hand so the check is exact. (Without
// the deadline: the prediction alone holds the budget.)
TEST(HybridEffects, MsBudgetCalibratesFromTheLastRtPass) {
  Scene s = makeSpheresScene();
  auto r =
      makeRenderer(s, "hybrid-budget", {"heuristic.budget_ms=10", "heuristic.deadline=0"}, 96, 54);
  r->renderFrame(0, s.camera);
  const HeuristicPass& h = heuristicOf(*r);
  const double threads = double(tbb::this_task_arena::max_concurrency());
  EXPECT_DOUBLE_EQ(h.lastBudget(), 10 * threads);  // prior: CPU ms per wall ms = workers
  const double cost1 = h.lastSelectedCost();
  ASSERT_GT(cost1, 0);
  EXPECT_LE(cost1, h.lastBudget());
  // Last frame's rt_stats is the heuristic's history input: its wall time set to 4 ms.
  std::any_cast<RtStats&>(r->context().history.at("rt_stats").record).ms = 4.0;
  r->renderFrame(1, s.camera);
  EXPECT_NEAR(h.lastBudget(), 10 * cost1 / 4.0, 1e-9 * h.lastBudget());
  EXPECT_LE(h.lastSelectedCost(), h.lastBudget());
  // The RT pass timed exactly the object-effects it traced (the next frame's costs per pixel).
  const RtStats& st = std::any_cast<const RtStats&>(r->context().input("rt_stats").record);
  for (size_t o = 0; o < s.objects.size(); ++o)
    for (size_t e = 0; e < size_t(kEffectCount); ++e) {
      if (st.pixels[o][e] > 0)
        EXPECT_GT(st.cpuMs[o][e], 0.0) << o << " " << e;
      else
        EXPECT_EQ(st.cpuMs[o][e], 0.0) << o << " " << e;
    }
}

// The deadline: T is `overcommit` times the calibrated budget, and the calibration learns from
// the cost of what was traced (here all of it: 1 s is far more than a 96 x 54 frame needs, so
// nothing is cut and the traced mask is the heuristic mask).
TEST(HybridEffects, DeadlineOvercommitsAndCalibratesOnTheTracedCost) {
  Scene s = makeSpheresScene();
  // A deadline (100 s) no frame reaches even on a loaded machine under the sanitizers.
  auto r = makeRenderer(s, "hybrid-budget",
                        {"heuristic.budget_ms=100000", "heuristic.overcommit=2"}, 96, 54);
  r->renderFrame(0, s.camera);
  const HeuristicPass& h = heuristicOf(*r);
  const double threads = double(tbb::this_task_arena::max_concurrency());
  EXPECT_DOUBLE_EQ(h.lastBudget(), 2 * 100000 * threads);
  const double cost1 = h.lastSelectedCost();
  ASSERT_GT(cost1, 0);
  const FrameContext& ctx = r->context();
  EXPECT_TRUE(sameBuffer(ctx.input("traced_mask"), ctx.input("heuristic_mask")));
  EXPECT_EQ(ctx.counters.at("rt_secondary/items_cut"), 0.0);
  std::any_cast<RtStats&>(r->context().history.at("rt_stats").record).ms = 4.0;
  r->renderFrame(1, s.camera);
  // Nothing was cut, so the traced cost is the selected cost (the same pixels at the same price).
  EXPECT_NEAR(h.lastBudget(), 2 * 100000 * cost1 / 4.0, 1e-6 * h.lastBudget());
}

// A deadline no tile can meet (everything selected, 1 fs to trace it) cuts every tile: nothing is
// traced and the frame is the zero-budget frame (everything from the fallbacks), pixel for pixel;
// a deadline nothing reaches draws what the same selection draws without one.
TEST(HybridEffects, DeadlineCutsToTheFallbackAndOtherwiseChangesNothing) {
  Scene s = makeSpheresScene();
  auto cut = makeRenderer(s, "hybrid-budget",
                          {"heuristic.budget_ms=1e-12", "heuristic.select_all=1"}, 96, 54);
  cut->renderFrame(0, s.camera);
  const FrameContext& ctx = cut->context();
  ASSERT_FALSE(heuristicOf(*cut).lastSelection().empty());  // something was selected...
  EXPECT_GT(ctx.counters.at("rt_secondary/items_cut"), 0.0);
  for (float v : ctx.input("traced_mask").data) ASSERT_EQ(v, 0.0f);  // ...and nothing traced
  auto none = makeRenderer(s, "hybrid-heuristic",
                           {"heuristic.budget=0", "deferred_shading.shadows=off",
                            "heuristic.shadows=budget", "ss_fallback.shadows=shadow_map"},
                           96, 54);
  none->renderFrame(0, s.camera);
  EXPECT_TRUE(sameBuffer(cut->output(), none->output()));

  auto late = makeRenderer(s, "hybrid-budget", {"heuristic.budget_ms=1e5"}, 96, 54);
  auto off =
      makeRenderer(s, "hybrid-budget", {"heuristic.budget_ms=1e5", "heuristic.deadline=0"}, 96, 54);
  late->renderFrame(0, s.camera);
  off->renderFrame(0, s.camera);
  EXPECT_EQ(heuristicOf(*late).lastSelection().size(), heuristicOf(*off).lastSelection().size());
  EXPECT_TRUE(
      sameBuffer(late->context().input("traced_mask"), late->context().input("heuristic_mask")));
  EXPECT_TRUE(sameBuffer(late->output(), off->output()));
}

// Under a deadline the work items (a tile and a node rank) go most relevant node first, then
// nearest the view centre, then by position; a tile holding two nodes is two items; every tile is
// prepared once.
TEST(HybridEffects, RankedTilesGoByRankThenCentre) {
  const int w = 64, h = 32;
  std::vector<View> views(1);
  views[0].camera.width = w;
  views[0].camera.height = h;
  Buffer mask(w, h, kEffectCount), ids(w, h, 1), order(2, 1, kEffectCount);
  std::fill(ids.data.begin(), ids.data.end(), -1.0f);
  // Object 0 (rank 1, reflection) fills x < 36, object 1 (rank 0, shadow) x >= 40 in the top
  // row of tiles; the bottom-right tile has nothing masked.
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (x < 36) {
        ids.at(x, y)[0] = 0;
        mask.at(x, y)[kReflection] = 1;
      } else if (x >= 40 && y < 16) {
        ids.at(x, y)[0] = 1;
        mask.at(x, y)[kShadow] = 1;
      }
    }
  std::fill(order.data.begin(), order.data.end(), -1.0f);
  order.at(0, 0)[kReflection] = 1;
  order.at(1, 0)[kShadow] = 0;
  EXPECT_EQ(nodeRank(&order, 1, kShadow), 0u);
  EXPECT_EQ(nodeRank(&order, 1, kReflection), kUnrankedNode);
  EXPECT_EQ(nodeRank(nullptr, 0, kReflection), kUnrankedNode);
  std::vector<std::array<int, 2>> prepared;
  std::mutex m;
  const std::vector<RankedTile> items =
      rankTiles(views, mask, ids, &order, [&](int x0, int y0, int, int) {
        std::lock_guard<std::mutex> lock(m);
        prepared.push_back({x0, y0});
      });
  EXPECT_EQ(prepared.size(), 8u);
  // Rank 0: tile (32, 0) (centre 8, -8 from the view's) before (48, 0) (24, -8). Rank 1: four
  // tiles 8 columns and 8 rows from the centre, by position, then the two at the left edge.
  const std::vector<std::array<int, 3>> expect = {{0, 32, 0}, {0, 48, 0},  {1, 16, 0}, {1, 16, 16},
                                                  {1, 32, 0}, {1, 32, 16}, {1, 0, 0},  {1, 0, 16}};
  ASSERT_EQ(items.size(), expect.size());
  for (size_t i = 0; i < items.size(); ++i) {
    EXPECT_EQ(int(items[i].rank), expect[i][0]) << i;
    EXPECT_EQ(items[i].x0, expect[i][1]) << i;
    EXPECT_EQ(items[i].y0, expect[i][2]) << i;
  }
}

// Raster shadow maps: under an occluder a point is in shadow, beside it lit, for a directional
// (orthographic map), a spot (its cone) and a point light (cube faces); lights that cast no
// shadows are always visible.
TEST(ShadowMaps, OccluderShadowsThePointBelowIt) {
  Scene s;
  Material m;
  m.doubleSided = true;
  const int mat = s.addMaterial(m), plane = s.addMesh(makePlane());
  Transform ground, roof;
  ground.scale = {10, 1, 10};
  roof.position = {0, 2, 0};
  s.addObject("ground", plane, mat, ground);
  s.addObject("roof", plane, mat, roof);  // [-1, 1]^2 at y = 2
  Light sun, spot, bulb, unshadowed;
  sun.type = LightType::Directional;
  sun.direction = {0, -1, 0};
  spot.type = LightType::Spot;
  spot.position = {0, 6, 0};
  spot.direction = {0, -1, 0};
  spot.outerConeDeg = 60;
  bulb.type = LightType::Point;
  bulb.position = {0, 5, 0};
  unshadowed = bulb;
  unshadowed.castsShadows = false;
  s.lights = {sun, spot, bulb, unshadowed};
  FrameScene fs;
  fs.update(s, 0, 0);
  ShadowMaps maps;
  maps.update(fs, 512);
  const Vec3 up{0, 1, 0};
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(maps.visibility(i, {0.2f, 0, -0.3f}, up), 0.0f) << "light " << i;
    EXPECT_EQ(maps.visibility(i, {3.0f, 0, 2.0f}, up), 1.0f) << "light " << i;
    EXPECT_EQ(maps.visibility(i, {0.0f, 2, 0.0f}, up), 1.0f) << "light " << i << " (the roof)";
  }
  EXPECT_EQ(maps.visibility(3, {0.2f, 0, -0.3f}, up), 1.0f);
  // Drawn once; a second update with nothing changed reuses them.
  maps.update(fs, 512);
  EXPECT_EQ(maps.redraws(), 1);

  // A single-sided roof facing the ground (its back towards every light) shadows the ground
  // as it blocks a shadow ray: the maps draw both faces.
  Scene one = s;
  Material single;
  single.doubleSided = false;
  one.objects[1].material = one.addMaterial(single);
  one.objects[1].local.rotationDeg = {180, 0, 0};
  FrameScene fsOne;
  fsOne.update(one, 0, 0);
  ShadowMaps facingDown;
  facingDown.update(fsOne, 512);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(facingDown.visibility(i, {0.2f, 0, -0.3f}, up), 0.0f) << "light " << i;
    EXPECT_EQ(facingDown.visibility(i, {3.0f, 0, 2.0f}, up), 1.0f) << "light " << i;
  }
}

// A caster the shadow rays pass (glass, a sheet that lets most light through, a material that
// casts no shadow) leaves the maps' depth: the point below is lit in the maps exactly when the
// traced transmittance through the roof keeps at least half the light (the binary map's nearer
// answer). Opaque and mostly opaque roofs still shadow it.
TEST(ShadowMaps, SeeThroughCastersLeaveTheDepthMaps) {
  struct Case {
    const char* name;
    float opacity, diffuse;
    bool casts;
  };
  const Case cases[] = {{"opaque", 1.0f, 0.5f, true},
                        {"glass", 0.0f, 0.02f, true},
                        {"mostly opaque", 0.7f, 0.2f, true},
                        {"mostly clear", 0.2f, 0.2f, true},
                        {"no shadow", 1.0f, 0.5f, false}};
  for (const Case& c : cases) {
    Scene s;
    Material ground;
    ground.doubleSided = true;
    Material roof = ground;
    roof.opacity = c.opacity;
    roof.diffuse = Vec3(c.diffuse);
    roof.castsShadows = c.casts;
    const int plane = s.addMesh(makePlane());
    Transform g, r;
    g.scale = {10, 1, 10};
    r.position = {0, 2, 0};
    s.addObject("ground", plane, s.addMaterial(ground), g);
    s.addObject("roof", plane, s.addMaterial(roof), r);
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = {0, -1, 0};
    s.lights = {sun};
    FrameScene fs;
    fs.update(s, 0, 0);
    ShadowMaps maps;
    maps.update(fs, 256);
    RayTracer rt;
    rt.update(fs);
    const Vec3 below{0.2f, 0.0f, -0.3f};
    Ray up;
    up.origin = below + Vec3(0, 1e-3f, 0);
    up.dir = {0, 1, 0};
    up.tfar = 100;
    const Vec3 t = rt.transmittance(up);
    const bool mostlyThrough = (t.x + t.y + t.z) / 3.0f >= 0.5f;
    EXPECT_EQ(maps.visibility(0, below, {0, 1, 0}), mostlyThrough ? 1.0f : 0.0f) << c.name;
    EXPECT_EQ(solidCaster(s.materials[1]), !mostlyThrough) << c.name;
  }
}

// The SIMD batch lookup is the scalar one, 16 points at a time, for every kind of map: random
// points under and around a roof, lit by a sun, a spot and a point light (a cube).
TEST(ShadowMaps, BatchLookupEqualsScalar) {
  Scene s;
  Material m;
  m.diffuse = {0.5f, 0.5f, 0.5f};
  const int mat = s.addMaterial(m), plane = s.addMesh(makePlane()), cube = s.addMesh(makeCube());
  Transform ground, roof, box;
  ground.scale = {10, 1, 10};
  roof.position = {0, 2, 0};
  box.position = {2, 0.5f, 1};
  box.scale = {0.5f, 0.5f, 0.5f};
  s.addObject("ground", plane, mat, ground);
  s.addObject("roof", plane, mat, roof);
  s.addObject("box", cube, mat, box);
  Light sun, spot, bulb;
  sun.type = LightType::Directional;
  sun.direction = normalize(Vec3{0.3f, -1, 0.2f});
  spot.type = LightType::Spot;
  spot.position = {0, 6, 0};
  spot.direction = {0, -1, 0};
  spot.outerConeDeg = 60;
  bulb.type = LightType::Point;
  bulb.position = {0.5f, 4, -0.5f};
  s.lights = {sun, spot, bulb};
  FrameScene fs;
  fs.update(s, 0, 0);
  ShadowMaps maps;
  maps.update(fs, 256);
  // On every instruction set the kernel was compiled for (CI's machines run AVX2).
  for (int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-4, 4);
    int lanes = 0, differ = 0, shadowed = 0;
    for (int batch = 0; batch < 400; ++batch) {
      float px[16], py[16], pz[16], nx[16], ny[16], nz[16], use[16], out[16];
      for (int k = 0; k < 16; ++k) {
        // On the ground (normal up) or on the box's top, a few points unused.
        const bool onBox = k % 5 == 0;
        px[k] = onBox ? 2 + u(rng) / 8 : u(rng);
        pz[k] = onBox ? 1 + u(rng) / 8 : u(rng);
        py[k] = onBox ? 1.0f : 0.0f;
        nx[k] = 0, ny[k] = 1, nz[k] = 0;
        use[k] = k % 7 == 3 ? 0.0f : 1.0f;
      }
      const int count = 1 + batch % 16;
      for (size_t light = 0; light < 3; ++light) {
        for (float& o : out) o = -1.0f;
        maps.visibilityBatch(light, px, py, pz, nx, ny, nz, use, count, out);
        for (int k = 0; k < 16; ++k) {
          if (k >= count || use[k] == 0) {
            EXPECT_EQ(out[k], -1.0f) << "unused lane " << k << " written";
            continue;
          }
          const float ref = maps.visibility(light, {px[k], py[k], pz[k]}, {0, 1, 0});
          ++lanes;
          shadowed += ref < 1.0f;
          if (out[k] != ref) {
            ++differ;
            EXPECT_NEAR(out[k], ref, 0.25f + 1e-6f);  // one tap at its threshold, at most
          }
        }
      }
    }
    EXPECT_GT(shadowed, lanes / 10) << hwy::TargetName(target);  // shadowed points covered too
    EXPECT_LE(differ, lanes / 200) << hwy::TargetName(target) << ": " << differ << " of " << lanes;
  }
  hwy::SetSupportedTargetsForTest(0);
}

// Static casters are drawn once; an animated caster is drawn again over their depth whenever it
// moves: its shadow follows it, the static shadow stays, and the static maps are not redrawn.
TEST(HybridEffects, ShadowMapsRedrawOnlyMovingCasters) {
  Scene s;
  Material m;
  m.diffuse = {0.5f, 0.5f, 0.5f};
  const int mat = s.addMaterial(m), plane = s.addMesh(makePlane()), cube = s.addMesh(makeCube());
  Transform ground, roof;
  ground.scale = {10, 1, 10};
  roof.position = {0, 2, 4};  // a static roof over z in [3, 5]
  s.addObject("ground", plane, mat, ground);
  s.addObject("roof", plane, mat, roof);
  const int box = s.addObject("box", cube, mat);
  Transform left, right;
  left.position = {-4, 2, 0};
  right.position = {4, 2, 0};
  left.scale = right.scale = {0.5f, 0.5f, 0.5f};
  s.objects[size_t(box)].animation = {{0.0f, left}, {1.0f, right}};
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = {0, -1, 0};
  s.lights = {sun};
  const Vec3 up{0, 1, 0};
  FrameScene fs;
  ShadowMaps maps;
  fs.update(s, 0, 0);
  maps.update(fs, 512);
  EXPECT_EQ(maps.visibility(0, {-4, 0, 0}, up), 0.0f);  // under the box
  EXPECT_EQ(maps.visibility(0, {4, 0, 0}, up), 1.0f);
  EXPECT_EQ(maps.visibility(0, {0, 0, 4}, up), 0.0f);  // under the roof
  fs.update(s, 1, 0);
  maps.update(fs, 512);
  EXPECT_EQ(maps.visibility(0, {-4, 0, 0}, up), 1.0f);  // the box has left
  EXPECT_EQ(maps.visibility(0, {4, 0, 0}, up), 0.0f);
  EXPECT_EQ(maps.visibility(0, {0, 0, 4}, up), 0.0f);
  EXPECT_EQ(maps.redraws(), 1);
  EXPECT_EQ(maps.movingRedraws(), 2);
  maps.update(fs, 512);  // nothing moved: nothing drawn
  EXPECT_EQ(maps.movingRedraws(), 2);
}

// A probe sees the scene from its object's centre: a red wall on +x, a green floor below, the
// sky elsewhere; the object itself is not in its own probe.
TEST(ReflectionProbes, SeeTheSceneAroundTheObject) {
  Scene s;
  Material red, green, ball;
  red.emission = {1, 0, 0};  // emission: the colour does not depend on the lights
  green.emission = {0, 1, 0};
  ball.emission = {0, 0, 1};
  s.skybox.color = {0.2f, 0.2f, 0.2f};
  const int plane = s.addMesh(makePlane());
  Transform wall, floor;
  wall.position = {3, 0, 0};
  wall.rotationDeg = {0, 0, 90};  // the plane's normal +y turned to -x: facing the ball
  wall.scale = {10, 1, 10};
  floor.position = {0, -3, 0};
  floor.scale = {10, 1, 10};
  s.addObject("wall", plane, s.addMaterial(red), wall);
  s.addObject("floor", plane, s.addMaterial(green), floor);
  const int b = s.addObject("ball", s.addMesh(makeUvSphere(16, 8)), s.addMaterial(ball));
  s.materials[size_t(s.objects[0].material)].doubleSided = true;
  FrameScene fs;
  fs.update(s, 0, 0);
  ReflectionProbes probes;
  std::vector<uint8_t> wanted(s.objects.size(), 0);
  wanted[size_t(b)] = 1;
  const ShadingContext shading = ShadingContext::from(s);
  EXPECT_EQ(probes.update(fs, shading, wanted, 32, 2, 8), 1);
  EXPECT_EQ(probes.update(fs, shading, wanted, 32, 2, 8), 0);  // nothing changed: reused
  auto near = [](Vec3 a, Vec3 e) { return length(a - e) < 0.02f; };
  EXPECT_TRUE(near(probes.lookup(s, b, {1, 0, 0}), {1, 0, 0}));
  EXPECT_TRUE(near(probes.lookup(s, b, {0, -1, 0}), {0, 1, 0}));
  EXPECT_TRUE(near(probes.lookup(s, b, {0, 1, 0}), {0.2f, 0.2f, 0.2f}));   // sky, not the ball
  EXPECT_TRUE(near(probes.lookup(s, b, {0, 0, -1}), {0.2f, 0.2f, 0.2f}));  // past the wall
  // Parallax: from a point near the wall looking at the floor's edge region the box proxy
  // bends the lookup, from the centre it is the plain lookup.
  const Bounds3 box{{-5, -3, -5}, {3, 5, 5}};
  EXPECT_TRUE(near(probes.lookupFrom(s, b, {0, 0, 0}, {0, -1, 0}, box), {0, 1, 0}));
  // Straight through the ball's centre a ray leaves undeviated, from the far side.
  Vec3 exit;
  const Vec3 out = probes.exitDirection(b, {-1, 0, 0}, {1, 0, 0}, 1.5f, exit);
  EXPECT_NEAR(out.x, 1.0f, 1e-5f);
  EXPECT_NEAR(exit.x, 1.0f, 1e-3f);
  // An object without a probe shows the sky.
  EXPECT_TRUE(near(probes.lookup(s, 0, {1, 0, 0}), {0.2f, 0.2f, 0.2f}));
  // Over capacity, the probe wanted longest ago is freed: the ball's, once the wall has one.
  std::vector<uint8_t> wallOnly(s.objects.size(), 0);
  wallOnly[0] = 1;
  EXPECT_EQ(probes.update(fs, shading, wallOnly, 32, 2, 1), 1);
  EXPECT_TRUE(near(probes.lookup(s, b, {1, 0, 0}), {0.2f, 0.2f, 0.2f}));
}

// probe_bake: the first frame draws the probe of every mirror and glass object, in view or not,
// so a camera that turns to them later draws none; without it each is drawn when its object
// first shows. Probes do not depend on the camera: in a still scene the images are the same
// either way (where objects move, a probe drawn earlier trails them by probe_refresh a frame).
TEST(HybridEffects, ProbesBakedOnTheFirstFrameLeaveTheImagesAsTheyWere) {
  Scene s = makeSpheresScene();
  for (Object& o : s.objects) o.animation = {};  // the bob held still
  size_t mirrorsAndGlass = 0;
  for (const Object& o : s.objects) {
    const Material& m = s.materials[size_t(o.material)];
    mirrorsAndGlass += m.reflectivity > 0 || m.opacity < 1 ? 1 : 0;
  }
  ASSERT_GT(mirrorsAndGlass, 1u);
  CameraDesc sky = s.camera;  // straight up: no object in view
  sky.lookAt = sky.position + Vec3(0, 1, 0);
  sky.up = Vec3(0, 0, 1);
  auto baked = makeRenderer(s, "hybrid-heuristic", {"heuristic.budget=0"}, 96, 54);
  auto drawnInView = makeRenderer(s, "hybrid-heuristic",
                                  {"heuristic.budget=0", "ss_fallback.probe_bake=0"}, 96, 54);
  auto drawn = [](const Renderer& r) {
    return r.context().counters.at("ss_fallback/probes_drawn");
  };
  baked->renderFrame(0, sky);
  drawnInView->renderFrame(0, sky);
  EXPECT_EQ(drawn(*baked), double(std::min<size_t>(mirrorsAndGlass, 32)));
  EXPECT_EQ(drawn(*drawnInView), 0.0);
  baked->renderFrame(1, s.camera);
  drawnInView->renderFrame(1, s.camera);
  EXPECT_EQ(drawn(*baked), 0.0);
  EXPECT_GT(drawn(*drawnInView), 0.0);
  EXPECT_TRUE(sameBuffer(baked->output(), drawnInView->output()));
}

// With nothing ray traced, the fallbacks (shadow maps, screen-space reflection and refraction)
// bring the image much closer to hybrid-all than the paper's rule (unshadowed, black mirrors).
TEST(HybridEffects, FallbacksStandInForUnselectedEffects) {
  Scene s = makeSpheresScene();
  const int w = 160, h = 90;
  auto all = test::renderOnce(s, "hybrid-all", w, h, s.camera);
  auto paper =
      makeRenderer(s, "hybrid-heuristic",
                   {"heuristic.budget=0", "deferred_shading.shadows=off",
                    "heuristic.shadows=budget", "ss_fallback.mode=off", "ss_fallback.shadows=off"},
                   w, h);
  auto fallback = makeRenderer(s, "hybrid-heuristic",
                               {"heuristic.budget=0", "deferred_shading.shadows=off",
                                "heuristic.shadows=budget", "ss_fallback.shadows=shadow_map"},
                               w, h);
  paper->renderFrame(0, s.camera);
  fallback->renderFrame(0, s.camera);
  EXPECT_TRUE(heuristicOf(*fallback).lastSelection().empty());
  const double paperErr = rmse(paper->output(), all->output());
  const double fallbackErr = rmse(fallback->output(), all->output());
  std::printf("RMSE vs hybrid-all: paper's rule %.4f, fallbacks %.4f\n", paperErr, fallbackErr);
  EXPECT_LT(fallbackErr, 0.8 * paperErr);
  EXPECT_GT(ssim(fallback->output(), all->output()), ssim(paper->output(), all->output()));
}
