// Classified shadows: the shadow maps decide a light where they are certain, a shadow ray the
// rest, and the image equals the ray-traced one; culling leaves the all-rays baseline as it was.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <string>

#include "core/error.h"
#include "eval/metrics/metrics.h"
#include "passes/heuristic/effect_channels.h"
#include "raster/shadow_maps.h"
#include "rt/whitted.h"
#include "scene/builtin_scenes.h"
#include "scene/loaders.h"
#include "shading/surface_resolve.h"
#include "test_util.h"

using namespace tandem;

namespace {

// A built-in scene as the command line loads it (cornell's ceiling emitter becomes its light).
Scene builtin(const std::string& name) {
  Scene s = makeBuiltinScene(name);
  if (s.lights.empty()) addLightsForEmissiveMeshes(s);
  return s;
}

// One frame through a built-in pipeline with `sets`; the renderer, to read buffers and counters.
std::unique_ptr<Renderer> render(const Scene& s, const std::string& pipeline,
                                 const std::vector<std::string>& sets, int w, int h) {
  Pipeline p = Pipeline::load(pipeline);
  for (const std::string& a : sets) p.setParam(a, "test");
  auto r = std::make_unique<Renderer>(s, std::move(p), RenderSettings{.width = w, .height = h});
  r->renderFrame(0, s.camera);
  return r;
}

// A floor (10 x 10 m at y = 0, object 0) and whatever else the test adds, lit by `light`.
Scene floorScene(const Light& light) {
  Scene s;
  Material m;
  m.doubleSided = true;
  const int mat = s.addMaterial(m);
  Transform ground;
  ground.scale = {5, 1, 5};
  s.addObject("floor", s.addMesh(makePlane()), mat, ground);
  s.lights = {light};
  return s;
}

SurfaceSample floorPoint(float x, float z) {
  SurfaceSample p;
  p.position = {x, 0, z};
  p.normal = p.geoNormal = {0, 1, 0};
  p.diffuse = {0.8f, 0.8f, 0.8f};
  p.object = 0;
  return p;
}

// Visibility of light 0 at 8 points by the given Whitted settings; rays per lane.
std::vector<float> visibilityOf(const Scene& s, const RayTracer& rt, const ShadowMaps* maps,
                                ShadowMode mode, const SurfaceSample* p, int n, int* rays,
                                uint8_t* classes = nullptr) {
  const ShadingContext shading = ShadingContext::from(s);
  WhittedSettings ws;
  ws.shadows = mode;
  Whitted w(rt, s, shading, ws);
  w.useShadowMaps(maps);
  Vec3 wo[8];
  for (int k = 0; k < n; ++k) wo[k] = Vec3(0, 1, 0);
  LightVisibility8 vis(s.lights.size());
  w.lightVisibility8(p, n, vis.data(), rays, wo, classes);
  return std::vector<float>(vis.data(), vis.data() + 8);  // light 0, red
}

// Light 0's visibility at 8 points traced (every shadow a ray) and classified (maps of
// `mapSize` texels first), with rays and classes per lane.
struct TwoWays {
  std::vector<float> byRays, byClass;
  int raysRt[8], raysCl[8];
  uint8_t classes[8];
};
TwoWays bothWays(const Scene& s, const ShadowMaps& maps, const SurfaceSample* p) {
  FrameScene fs;
  fs.update(s, 0, 0);
  RayTracer rt;
  rt.update(fs);
  TwoWays w;
  w.byRays = visibilityOf(s, rt, nullptr, ShadowMode::Rays, p, 8, w.raysRt);
  w.byClass = visibilityOf(s, rt, &maps, ShadowMode::Classified, p, 8, w.raysCl, w.classes);
  return w;
}

}  // namespace

// On every built-in scene the classified image is the ray-traced one (PSNR >= 45 dB, the
// issue's bound; culling off in both so only the classification differs), and the maps decide
// most light-pixel pairs without a ray.
TEST(ClassifiedShadows, EqualRayTracedShadowsOnEveryBuiltinScene) {
  for (const std::string& name : builtinSceneNames()) {
    const Scene s = builtin(name);
    auto rays = render(s, "hybrid-all", {"rt_secondary.shadows=rays", "rt_secondary.shadow_cull=0"},
                       192, 108);
    auto classified =
        render(s, "hybrid-all", {"rt_secondary.shadows=classified", "rt_secondary.shadow_cull=0"},
               192, 108);
    const double db = psnr(rays->context().input("output"), classified->context().input("output"));
    EXPECT_GE(db, 45.0) << name;
    const auto& c = classified->context().counters;
    const double traced = c.at("rt_secondary/shadow_traced");
    const double decided = c.at("rt_secondary/shadow_lit") + c.at("rt_secondary/shadow_shadowed");
    EXPECT_LT(traced, decided) << name;
    EXPECT_EQ(rays->context().counters.at("rt_secondary/shadow_lit"), 0.0) << name;
  }
}

// Lights with a range draw into their maps only the casters that reach inside it: wherever such
// a light reaches, its maps classify and filter exactly as maps holding every caster do (the
// same lights without their range). Cornell's block and spheres under 60 small lights, at the
// surfaces camera rays find.
TEST(ClassifiedShadows, RangedLightsKeepTheirCasters) {
  Scene ranged = builtin("cornell");
  ranged.lights.clear();
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 60; ++i) {
    Light l;
    l.position = {u(rng) * 1.6f - 0.8f, 0.2f + u(rng) * 1.6f, u(rng) * 1.6f - 0.8f};
    l.range = 0.3f + 0.9f * u(rng);
    ranged.lights.push_back(l);
  }
  Scene whole = ranged;
  for (Light& l : whole.lights) l.range = 0.0f;
  FrameScene fr, fw;
  fr.update(ranged, 0, 0);
  fw.update(whole, 0, 0);
  ShadowMaps mr, mw;
  mr.update(fr, 256);
  mw.update(fw, 256);
  RayTracer rt;
  rt.update(fr);
  int compared = 0, shadowed = 0;
  for (int k = 0; k < 4000; ++k) {
    Ray r;
    r.origin = {0, 1, 3.5f};
    r.dir = normalize(Vec3(u(rng) - 0.5f, u(rng) - 0.6f, -1.0f));
    const Hit h = rt.intersect(r);
    if (!h.valid()) continue;
    const float tuv[3] = {h.t, h.u, h.v};
    const SurfaceSample s =
        resolveSurface(*rt.frame(), h.object, h.prim, r.origin, r.dir, 0.0f, tuv);
    for (size_t i = 0; i < ranged.lights.size(); ++i) {
      if (length(ranged.lights[i].position - s.position) > ranged.lights[i].range) continue;
      const ShadowClass a = mr.classify(i, s.position, s.geoNormal, s.object);
      ASSERT_EQ(a, mw.classify(i, s.position, s.geoNormal, s.object)) << k << " light " << i;
      const float v = mr.visibility(i, s.position, s.geoNormal);
      ASSERT_EQ(v, mw.visibility(i, s.position, s.geoNormal)) << k << " light " << i;
      ++compared;
      shadowed += a == ShadowClass::Shadowed;
    }
  }
  EXPECT_GT(compared, 2000);
  EXPECT_GT(shadowed, 20);  // some casters inside a range do shadow
}

// Maps only for the lights that reach a surface in view: lights far behind the camera get none,
// and a light without maps that is asked about anyway is left to a ray, never called lit.
TEST(ClassifiedShadows, MapsOnlyForLightsReachingTheView) {
  Scene s = builtin("cornell");
  s.lights.clear();
  for (int i = 0; i < 40; ++i) {
    Light l;
    l.range = 0.6f;
    l.intensity = 0.2f;
    // Half inside the box, half 20 m behind the camera.
    l.position = i % 2 == 0 ? Vec3(-0.9f + 0.09f * float(i / 2), 1.2f, 0.0f)
                            : Vec3(float(i) * 0.1f, 1.0f, 25.0f);
    s.lights.push_back(l);
  }
  auto r = render(s, "hybrid-heuristic", {"rt_secondary.shadows=classified"}, 96, 54);
  const auto& c = r->context().counters;
  EXPECT_EQ(c.at("shadow_maps/mapped_lights"), 20.0);
  for (float v : r->output().data) ASSERT_TRUE(std::isfinite(v));
  FrameScene fs;
  fs.update(s, 0, 0);
  ShadowMaps maps;
  std::vector<uint8_t> wanted(s.lights.size(), 0);
  wanted[0] = 1;
  maps.update(fs, 128, &wanted);
  EXPECT_EQ(maps.mappedLights(), 1);
  const Vec3 floor{-0.7f, 0.0f, 0.0f}, up{0, 1, 0};
  EXPECT_EQ(maps.classify(2, floor, up, -1), ShadowClass::Traced);  // no maps: a ray decides
  wanted[2] = 1;  // comes into view: drawn alone, the first kept
  maps.update(fs, 128, &wanted);
  EXPECT_EQ(maps.mappedLights(), 2);
  EXPECT_EQ(maps.redraws(), 1);
}

// A rod a tenth of a cube-map texel wide between a point light and the floor: the ordinary map
// does not see it (no texel centre falls on it), the conservative map does, so the floor under
// it is never classified lit and keeps its ray-traced shadow.
TEST(ClassifiedShadows, ThinCasterKeepsItsRayTracedShadow) {
  Light bulb;
  bulb.type = LightType::Point;
  bulb.position = {0, 4, 0};
  bulb.intensity = 20;
  Scene s = floorScene(bulb);
  constexpr int kMapSize = 64;  // cube faces of 32 texels over 92 degrees
  const float texelAt2m = 2.0f * 2.0f * std::tan(radians(46.0f)) / float(kMapSize / 2);
  Material m;
  const int rodMat = s.addMaterial(m);
  Transform rod;
  rod.position = {0.013f, 2, 0.021f};                        // off the texel grid's centres
  rod.scale = {1.5f, 0.05f * texelAt2m, 0.05f * texelAt2m};  // makeCube spans [-1, 1]
  s.addObject("rod", s.addMesh(makeCube()), rodMat, rod);
  FrameScene fs;
  fs.update(s, 0, 0);
  ShadowMaps maps;
  maps.update(fs, kMapSize);
  // Points on the floor under the rod's axis: the rod's shadow is 2x its width at y = 0.
  SurfaceSample p[8];
  for (int k = 0; k < 8; ++k) p[k] = floorPoint(-2.0f + 0.5f * float(k) + 0.026f, 0.042f);
  const TwoWays w = bothWays(s, maps, p);
  const std::vector<float>&byRays = w.byRays, &byClass = w.byClass;
  const uint8_t* classes = w.classes;
  int unseen = 0;
  for (int k = 0; k < 8; ++k) {
    EXPECT_EQ(byRays[size_t(k)], 0.0f) << "the rod shadows point " << k;
    EXPECT_EQ(byClass[size_t(k)], byRays[size_t(k)]) << k;
    EXPECT_NE(ShadowClass(classes[k]), ShadowClass::Lit) << k;
    unseen += maps.visibility(0, p[k].position, p[k].normal) == 1.0f ? 1 : 0;
  }
  EXPECT_GE(unseen, 6) << "the ordinary map should miss most of a rod this thin";
}

// A roof over the floor under a sun: points deep in its shadow are shadowed and points far
// from it lit, decided by the maps alone (no ray), with the ray-traced values.
TEST(ClassifiedShadows, CertainPixelsGetNoRay) {
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = normalize(Vec3(0.3f, -1, 0.2f));
  sun.intensity = 3;
  Scene s = floorScene(sun);
  Material m;
  const int mat = s.addMaterial(m);
  Transform roof;
  roof.position = {0, 2, 0};
  roof.scale = {1.5f, 1, 1.5f};
  s.addObject("roof", s.addMesh(makePlane()), mat, roof);
  FrameScene fs;
  fs.update(s, 0, 0);
  ShadowMaps maps;
  maps.update(fs, 512);
  // The roof's shadow is centred at 2 * (0.3, 0.2) = (0.6, 0.4).
  SurfaceSample p[8] = {floorPoint(0.6f, 0.4f),  floorPoint(0.2f, 0.1f), floorPoint(1.0f, 0.8f),
                        floorPoint(0.9f, -0.2f), floorPoint(3.5f, 3.5f), floorPoint(-4.0f, 3.0f),
                        floorPoint(3.0f, -4.0f), floorPoint(4.2f, 0.3f)};
  const TwoWays w = bothWays(s, maps, p);
  const std::vector<float>&byRays = w.byRays, &byClass = w.byClass;
  const int *raysRt = w.raysRt, *raysCl = w.raysCl;
  const uint8_t* classes = w.classes;
  for (int k = 0; k < 8; ++k) {
    const bool inShadow = k < 4;
    EXPECT_EQ(byRays[size_t(k)], inShadow ? 0.0f : 1.0f) << k;
    EXPECT_EQ(raysRt[k], 1) << k;
    EXPECT_EQ(ShadowClass(classes[k]), inShadow ? ShadowClass::Shadowed : ShadowClass::Lit) << k;
    EXPECT_EQ(raysCl[k], 0) << k;
    EXPECT_EQ(byClass[size_t(k)], byRays[size_t(k)]) << k;
  }
  // A transparent roof is never "shadowed" by the maps: its shadow is partial (Listing 8b).
  s.materials[size_t(mat)].opacity = 0.5f;
  FrameScene glass;
  glass.update(s, 0, 0);
  ShadowMaps glassMaps;
  glassMaps.update(glass, 512);
  EXPECT_EQ(glassMaps.classify(0, p[0].position, p[0].geoNormal, 0), ShadowClass::Traced);
}

// Culling (a light below 0.4 % of the surface's unshadowed light gets no query) keeps rt-only,
// the all-rays baseline, within PSNR 50 dB of its image without culling on every built-in scene.
TEST(ClassifiedShadows, CullingKeepsRtOnlyWithin50dB) {
  for (const std::string& name : builtinSceneNames()) {
    const Scene s = builtin(name);
    auto exact = render(s, "rt-only", {"rt_whitted.shadow_cull=0"}, 192, 108);
    auto culled = render(s, "rt-only", {}, 192, 108);
    EXPECT_GE(psnr(exact->context().input("output"), culled->context().input("output")), 50.0)
        << name;
    EXPECT_GE(culled->context().counters.at("rt_whitted/shadow_culled"),
              exact->context().counters.at("rt_whitted/shadow_culled"))
        << name;
  }
}

// The maps see the whole scene, not only the screen: at surface points anywhere (as reflection
// and refraction rays and lens rays hit them), whatever the maps decide agrees with the shadow
// ray.
TEST(ClassifiedShadows, DecisionsAgreeWithShadowRaysAnywhereInTheScene) {
  const Scene s = builtin("spheres");
  FrameScene fs;
  fs.update(s, 0, 0);
  ShadowMaps maps;
  maps.update(fs, 1024);
  RayTracer rt;
  rt.update(fs);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int decided = 0, wrong = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const size_t o = size_t(u(rng) * float(fs.objects.size())) % fs.objects.size();
    const std::vector<uint32_t>& idx = s.meshes[size_t(s.objects[o].mesh)].indices;
    const size_t t = 3 * (size_t(u(rng) * float(idx.size() / 3)) % (idx.size() / 3));
    const Vec3 a = fs.objects[o].positions[idx[t]], b = fs.objects[o].positions[idx[t + 1]],
               c = fs.objects[o].positions[idx[t + 2]];
    float r1 = u(rng), r2 = u(rng);
    if (r1 + r2 > 1) r1 = 1 - r1, r2 = 1 - r2;
    SurfaceSample p;
    p.position = a + (b - a) * r1 + (c - a) * r2;
    p.normal = p.geoNormal = normalize(cross(b - a, c - a));
    p.object = int(o);
    for (size_t i = 0; i < s.lights.size(); ++i) {
      const LightSample ls = sampleLight(s.lights[i], p.position);
      if (dot(p.normal, ls.wi) <= 0) continue;  // facing away: culled, never classified
      const ShadowClass k = maps.classify(i, p.position, p.geoNormal, p.object);
      if (k == ShadowClass::Traced) continue;
      ++decided;
      const Vec3 v = rt.transmittance(shadowRayTowards(p, ls, 0.0f));
      const bool bad =
          (k == ShadowClass::Lit) != (v.x == 1.0f) || (k == ShadowClass::Shadowed && v.x != 0);
      if (bad && wrong < 12)
        std::printf("light %zu object %zu class %d ray %g at %g %g %g n %g %g %g\n", i, o, int(k),
                    v.x, p.position.x, p.position.y, p.position.z, p.normal.x, p.normal.y,
                    p.normal.z);
      wrong += bad;
    }
  }
  EXPECT_GT(decided, 3000);
  EXPECT_LE(wrong, decided / 500) << wrong << " of " << decided;  // <= 0.2 %
}

// With every shadow traced and no culling, classified-shadow machinery is out of the way: the
// image is bit for bit the one of a Whitted tracer that never heard of shadow maps (the
// pipeline's rt_secondary against shading the G-buffer samples with plain shadow rays).
TEST(ClassifiedShadows, RaysWithoutCullingAreExactlyTheShadowRays) {
  const Scene s = builtin("cornell");
  auto r =
      render(s, "hybrid-all", {"rt_secondary.shadows=rays", "rt_secondary.shadow_cull=0"}, 64, 48);
  auto again =
      render(s, "hybrid-all", {"rt_secondary.shadows=rays", "rt_secondary.shadow_cull=0"}, 64, 48);
  const Buffer& a = r->context().input("shadow");
  EXPECT_EQ(a.data, again->context().input("shadow").data);
  // Each lane's visibility equals Whitted::lightVisibility (one ray per light, no maps).
  FrameScene fs;
  fs.update(s, 0, 0);
  RayTracer rt;
  rt.update(fs);
  const ShadingContext shading = ShadingContext::from(s);
  WhittedSettings ws;
  ws.shadows = ShadowMode::Rays;
  Whitted w(rt, s, shading, ws);
  SurfaceSample p[8];
  for (int k = 0; k < 8; ++k) p[k] = floorPoint(-0.8f + 0.2f * float(k), 0.1f), p[k].object = 0;
  LightVisibility8 vis(s.lights.size());
  w.lightVisibility8(p, 8, vis.data());
  for (int k = 0; k < 8; ++k) {
    std::vector<Vec3> one(s.lights.size());
    w.lightVisibility(p[k], one.data());
    for (size_t i = 0; i < s.lights.size(); ++i)
      EXPECT_EQ(vis.data()[3 * i * 8 + size_t(k)], one[i].x);
  }
}

// Bad values of the new settings are errors naming the field.
TEST(ClassifiedShadows, BadSettingsNameTheField) {
  Pipeline p = Pipeline::load("hybrid-all");
  auto problem = [&](const std::string& set) {
    try {
      p.setParam(set, "cli");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(problem("rt_secondary.shadows=sometimes").find("rt_secondary.shadows"),
            std::string::npos);
  EXPECT_NE(problem("rt_secondary.shadow_cull=-0.1").find("rt_secondary.shadow_cull"),
            std::string::npos);
  EXPECT_NE(problem("rt_secondary.shadow_map_size=3").find("rt_secondary.shadow_map_size"),
            std::string::npos);
  EXPECT_EQ(problem("rt_secondary.shadows=maps"), "accepted");
}

// heuristic.shadows = all: every visible pixel's shadows are traced (classified shadows are
// cheap), and the budget buys only reflections and refractions: with no budget none are traced.
TEST(ClassifiedShadows, HeuristicTracesEveryShadowWhenAskedTo) {
  const Scene s = builtin("spheres");
  auto r = render(s, "hybrid-heuristic",
                  {"deferred_shading.shadows=off", "heuristic.shadows=all", "heuristic.budget=0"},
                  96, 54);
  const Buffer& mask = r->context().input("heuristic_mask");
  const Buffer& ids = r->context().input("object_id");
  size_t visible = 0;
  for (size_t i = 0; i < ids.pixelCount(); ++i) {
    const float* m = &mask.data[3 * i];
    const bool object = ids.data[i] >= 0;
    visible += object ? 1 : 0;
    EXPECT_EQ(m[0], object ? 1.0f : 0.0f) << i;
    EXPECT_EQ(m[1], 0.0f) << i;
    EXPECT_EQ(m[2], 0.0f) << i;
  }
  EXPECT_GT(visible, ids.pixelCount() / 2);
  // With a budget, mirrors and glass are selected on top (their nodes alone carry a cost).
  auto more = render(s, "hybrid-heuristic",
                     {"deferred_shading.shadows=off", "heuristic.shadows=all"}, 96, 54);
  EXPECT_GT(more->context().counters.at("heuristic/selected"), 0.0);
  EXPECT_EQ(r->context().counters.at("heuristic/selected"), 0.0);
}

// heuristic.shadows = maps (what hybrid-heuristic ships with): no shadow is traced, ss_fallback's
// maps shadow every visible pixel, and the budget that bought shadows in the paper's rule buys
// more reflections and refractions.
TEST(ClassifiedShadows, HeuristicLeavesEveryShadowToTheMapsWhenAskedTo) {
  const Scene s = builtin("spheres");
  auto maps = render(s, "hybrid-heuristic",
                     {"deferred_shading.shadows=off", "ss_fallback.shadows=shadow_map",
                      "heuristic.shadows=maps", "heuristic.budget=1000"},
                     96, 54);
  auto paper = render(s, "hybrid-heuristic",
                      {"deferred_shading.shadows=off", "ss_fallback.shadows=shadow_map",
                       "heuristic.shadows=budget", "heuristic.budget=1000"},
                      96, 54);
  const Buffer& mask = maps->context().input("heuristic_mask");
  const Buffer& paperMask = paper->context().input("heuristic_mask");
  const Buffer& fallback = maps->context().input("fallback");
  const Buffer& ids = maps->context().input("object_id");
  size_t effects = 0, paperEffects = 0, paperShadows = 0;
  for (size_t i = 0; i < ids.pixelCount(); ++i) {
    const float* m = &mask.data[3 * i];
    const float* pm = &paperMask.data[3 * i];
    EXPECT_EQ(m[kShadow], 0.0f) << i;
    if (ids.data[i] >= 0) {
      EXPECT_EQ(fallback.data[i * fallback::kChannels + fallback::kCoversShadow], 1.0f) << i;
    }
    effects += m[kReflection] > 0.5f || m[kRefraction] > 0.5f;
    paperEffects += pm[kReflection] > 0.5f || pm[kRefraction] > 0.5f;
    paperShadows += pm[kShadow] > 0.5f;
  }
  EXPECT_GT(paperShadows, 0u);  // the paper's rule spends some of the budget on shadows
  EXPECT_GT(effects, paperEffects);
  EXPECT_GT(maps->context().counters.at("heuristic/selected"),
            paper->context().counters.at("heuristic/selected"));
}

// hybrid-heuristic's deferred shading shades with the shadow maps (deferred_shading.shadows =
// shadow_map): the image ss_fallback's map shadows and blend's eq. 4 gave, to within a few units
// in the last place (L - (1 - S) is the same sum, L weighed once), with ss_fallback shadowing
// nothing; the map shadows darken a share of the pixels.
TEST(ClassifiedShadows, DeferredShadingWithMapsGivesTheFallbacksImage) {
  for (const char* name : {"spheres", "cornell", "atrium"}) {
    const Scene s = builtin(name);
    auto shaded = render(s, "hybrid-heuristic", {}, 96, 54);
    auto fallback =
        render(s, "hybrid-heuristic",
               {"deferred_shading.shadows=off", "ss_fallback.shadows=shadow_map"}, 96, 54);
    auto unshadowed = render(s, "hybrid-heuristic", {"deferred_shading.shadows=off"}, 96, 54);
    const Buffer &a = shaded->context().input("composite"),
                 &b = fallback->context().input("composite");
    ASSERT_EQ(a.data.size(), b.data.size());
    for (size_t i = 0; i < a.data.size(); ++i)
      ASSERT_NEAR(a.data[i], b.data[i], 4e-7f * std::max(1.0f, std::abs(b.data[i])))
          << name << " value " << i;
    const Buffer& fb = shaded->context().input("fallback");
    for (size_t i = 0; i < fb.pixelCount(); ++i)
      ASSERT_EQ(fb.data[i * fallback::kChannels + fallback::kCoversShadow], 0.0f) << name << i;
    const Buffer &lit = shaded->context().input("hdr"), &bare = unshadowed->context().input("hdr");
    size_t darker = 0;
    for (size_t i = 0; i < lit.pixelCount(); ++i)
      darker += luminance(lit.rgb(int(i % 96), int(i / 96))) <
                0.9f * luminance(bare.rgb(int(i % 96), int(i / 96)));
    EXPECT_GT(darker, lit.pixelCount() / 50) << name << ": the maps shadow almost nothing";
  }
}

// A pipeline whose deferred shading shades with the maps cannot also take shadows from that light
// (traced by the heuristic's selection, or ss_fallback's): loading, the CLI's --set and each frame
// say so, naming the passes; turned off, the paper's rule runs.
TEST(ClassifiedShadows, ShadowsAreNotTakenTwice) {
  Pipeline p = Pipeline::load("hybrid-heuristic");
  EXPECT_NO_THROW(p.checkShadows("test"));
  p.setParam("heuristic.shadows=budget", "test");
  try {
    p.checkShadows("test");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("heuristic"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("deferred_shading"), std::string::npos) << e.what();
  }
  const Scene s = builtin("spheres");
  {
    Pipeline q = Pipeline::load("hybrid-heuristic");
    q.setParam("ss_fallback.shadows=shadow_map", "test");
    Renderer r(s, std::move(q), RenderSettings{.width = 32, .height = 18});
    EXPECT_THROW(r.renderFrame(0, s.camera), InputError);
  }
  p.setParam("deferred_shading.shadows=off", "test");
  EXPECT_NO_THROW(p.checkShadows("test"));
  const std::string doubled = R"({"name": "doubled", "passes": [
      {"type": "raster_gbuffer"}, {"type": "deferred_shading", "params": {"shadows": "shadow_map"}},
      {"type": "heuristic"}, {"type": "rt_secondary"}, {"type": "ss_fallback",
      "params": {"shadows": "off"}}, {"type": "blend"}, {"type": "tonemap",
      "inputs": {"hdr": "composite"}}]})";
  EXPECT_THROW(Pipeline::fromJson(Json::parse(doubled), "doubled.json"), InputError);
}

namespace {

// Peak resident memory of this process so far (VmHWM), in bytes; 0 where /proc is not there.
double peakResidentBytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) * 1024.0;
  return 0;
}

}  // namespace

// Shadow maps for many lights share a budget of texels: the size drops (a multiple of 32, at
// least 32) only when the faces would exceed it, so the usual scenes keep their maps.
TEST(ShadowMapBudget, ManyLightsGetSmallerMapsNotMoreMemory) {
  Scene s = builtin("cornell");
  EXPECT_EQ(budgetedShadowMapSize(s, 1024), 1024);
  Light point;
  point.type = LightType::Point;
  s.lights.assign(1000, point);  // 6000 cube faces
  const int size = budgetedShadowMapSize(s, 1024);
  EXPECT_EQ(size % 32, 0);
  EXPECT_LE(6000.0 * size * size, kMaxShadowTexels);
  EXPECT_GT(6000.0 * (size + 32) * (size + 32), kMaxShadowTexels);
  // A sun's one map has twice the side: it counts as four.
  Scene sunny = builtin("cornell");
  Light sun;
  sun.type = LightType::Directional;
  sunny.lights.assign(100, sun);
  const int sunSize = budgetedShadowMapSize(sunny, 8192);
  EXPECT_EQ(shadowFaceSize(sun, sunSize), 2 * sunSize);
  EXPECT_LE(100.0 * 4.0 * sunSize * sunSize, kMaxShadowTexels);
  EXPECT_GT(100.0 * 4.0 * (sunSize + 32) * (sunSize + 32), kMaxShadowTexels);
  for (Light& l : s.lights) l.castsShadows = false;  // no maps at all
  EXPECT_EQ(budgetedShadowMapSize(s, 1024), 1024);
  // A thousand point lights render through the hybrid (maps for classified shadows and the
  // fallback) within 2 GiB, every pixel finite.
  Scene many = builtin("cornell");
  many.lights.clear();
  for (int i = 0; i < 1000; ++i) {
    Light l = point;
    l.position = {float(i % 32) / 32.0f - 0.5f, 1.5f, float(i / 32) / 32.0f - 0.5f};
    l.intensity = 0.1f;
    many.lights.push_back(l);
  }
  const auto r = render(many, "hybrid-heuristic", {}, 64, 36);
  for (float v : r->output().data) ASSERT_TRUE(std::isfinite(v));
  const double peak = peakResidentBytes();
  if (peak > 0) {
    EXPECT_LT(peak, 2.0 * 1024 * 1024 * 1024) << peak / 1048576 << " MiB";
  }
}
