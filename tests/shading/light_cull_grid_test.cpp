// The light cull grid lists every light that reaches a region (a superset, ascending), so shading
// through it equals shading every light, bit for bit, while visiting far fewer lights.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <random>

#include "core/color.h"
#include "rt/path_tracer.h"
#include "rt/ray_tracer.h"
#include "rt/sampler.h"
#include "rt/whitted.h"
#include "scene/builtin_scenes.h"
#include "scene/frame_scene.h"
#include "shading/blinn_phong.h"
#include "shading/light_cull_grid.h"
#include "shading/shade_batch.h"
#include "shading/surface_resolve.h"

using namespace tandem;

namespace {

// Lights of every kind in a 20 m cube: mostly small ranged points and spots, a few ranged ones
// larger than the cube, and lights without a range (directional, point, spot).
std::vector<Light> mixedLights(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Light> lights;
  for (int i = 0; i < n; ++i) {
    Light l;
    const int kind = i % 10;
    l.type = kind < 6 ? LightType::Point : (kind < 9 ? LightType::Spot : LightType::Directional);
    l.position = {u(rng) * 20 - 10, u(rng) * 20 - 10, u(rng) * 20 - 10};
    l.direction = normalize(Vec3(u(rng) - 0.5f, -1.0f, u(rng) - 0.5f));
    l.range = 0.2f + 2.0f * u(rng);
    if (i % 37 == 0) l.range = 40.0f;  // reaches everything
    if (i % 23 == 0) l.range = 0.0f;   // no range: everywhere
    l.outerConeDeg = 20 + 60 * u(rng);
    l.innerConeDeg = l.outerConeDeg * 0.5f;
    lights.push_back(l);
  }
  return lights;
}

ShadingContext contextOf(const std::vector<Light>& lights) {
  ShadingContext c;
  for (const Light& l : lights) c.lights.push_back(PreparedLight::from(l));
  return c;
}

}  // namespace

// For points, small boxes, boxes outside the lights' region and huge boxes: the grid's list is
// ascending and unique, and lightsReaching through it keeps every light the test over every
// light keeps that can reach the box.
TEST(LightCullGrid, ListsEveryLightThatReaches) {
  ShadingContext ctx = contextOf(mixedLights(600, 3));
  ShadingContext all = ctx;
  ctx.cull = LightCullGrid::build(ctx.lights, 0);
  ASSERT_TRUE(ctx.cull);
  EXPECT_GT(ctx.cull->cells(0) * ctx.cull->cells(1) * ctx.cull->cells(2), 100);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<uint32_t> near, fast, exact;
  size_t visited = 0, queries = 0;
  for (int q = 0; q < 4000; ++q) {
    const float spread = q % 4 == 0 ? 30.0f : 12.0f;  // some points beyond the lights
    const Vec3 c{u(rng) * 2 * spread - spread, u(rng) * 2 * spread - spread,
                 u(rng) * 2 * spread - spread};
    const float size = q % 3 == 0 ? 0.0f : (q % 3 == 1 ? 0.3f * u(rng) : 15.0f * u(rng));
    Bounds3 box;
    box.extend(c);
    box.extend(c + Vec3(size, 0.5f * size, size));
    ctx.cull->candidates(box, near);
    ASSERT_TRUE(std::is_sorted(near.begin(), near.end()));
    ASSERT_EQ(std::adjacent_find(near.begin(), near.end()), near.end());
    lightsReaching(ctx, box, fast);
    lightsReaching(all, box, exact);
    // The grid may leave out more than the bounding-sphere test (it tests the box itself), but
    // only ranged lights whose sphere misses the box.
    ASSERT_TRUE(std::includes(exact.begin(), exact.end(), fast.begin(), fast.end()));
    std::vector<uint32_t> dropped;
    std::set_difference(exact.begin(), exact.end(), fast.begin(), fast.end(),
                        std::back_inserter(dropped));
    for (const uint32_t i : dropped) {
      const PreparedLight& l = ctx.lights[i];
      ASSERT_GT(l.range, 0.0f) << "query " << q << " light " << i;
      const Vec3 nearest = vmin(vmax(l.position, box.lo), box.hi);
      ASSERT_GT(length(nearest - l.position), l.range) << "query " << q << " light " << i;
    }
    if (size <= 0.3f) {
      ASSERT_EQ(fast, exact) << "query " << q;  // one or a few cells
    }
    if (size == 0.0f) visited += near.size(), ++queries;
  }
  // A point sees the lights without a range and the few that reach it, not all 600.
  EXPECT_LT(double(visited) / double(queries), 120.0);
  // A box that is not finite gets every light.
  Bounds3 bad;
  bad.extend(Vec3(NAN, 0, 0));
  ctx.cull->candidates(bad, near);
  EXPECT_EQ(near.size(), ctx.lights.size());
}

TEST(LightCullGrid, NoGridWhereNothingCulls) {
  std::vector<Light> lights(40);  // points without a range
  EXPECT_FALSE(LightCullGrid::build(contextOf(lights).lights));
  for (Light& l : lights) l.range = 1.0f;
  EXPECT_TRUE(LightCullGrid::build(contextOf(lights).lights));
  lights.resize(3);  // too few to be worth a grid by default
  EXPECT_FALSE(LightCullGrid::build(contextOf(lights).lights));
}

// Cornell with 200 small ranged lights: Whitted's shading of primary hits (shadow rays, with
// and without classified shadow maps) and the path tracer's next-event estimation give the same
// radiance, bit for bit, with the grid as without it.
TEST(LightCullGrid, RenderersUnchangedByTheGrid) {
  Scene scene = makeBuiltinScene("cornell");
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 200; ++i) {
    Light l;
    l.position = {u(rng) * 1.8f - 0.9f, u(rng) * 1.8f + 0.1f, u(rng) * 1.8f - 0.9f};
    l.range = 0.2f + 0.4f * u(rng);
    l.intensity = 0.05f;
    scene.lights.push_back(l);
  }
  const ShadingContext grid = ShadingContext::from(scene);
  ASSERT_TRUE(grid.cull);
  ShadingContext plain = grid;
  plain.cull = nullptr;
  FrameScene fs;
  fs.update(scene, 0, 0);
  RayTracer rt;
  rt.update(fs);
  ShadowMaps maps;
  maps.update(fs, 128);
  const Vec3 eye{0, 1, 3.5f};
  int lit = 0;
  for (ShadowMode mode : {ShadowMode::Rays, ShadowMode::Classified}) {
    WhittedSettings ws;
    ws.shadows = mode;
    Whitted a(rt, scene, grid, ws), b(rt, scene, plain, ws);
    a.useShadowMaps(&maps);
    b.useShadowMaps(&maps);
    for (int block = 0; block < 64; ++block) {
      SurfaceSample s[8];
      Vec3 d[8], ra[8], rb[8];
      int n = 0;
      for (int k = 0; k < 8; ++k) {
        Ray r;
        r.origin = eye;
        r.dir = normalize(Vec3(u(rng) - 0.5f, u(rng) - 0.6f, -1.0f));
        const Hit h = rt.intersect(r);
        if (!h.valid()) continue;
        const float tuv[3] = {h.t, h.u, h.v};
        s[n] = resolveSurface(*rt.frame(), h.object, h.prim, eye, r.dir, 0.0f, tuv);
        d[n++] = r.dir;
      }
      a.shadePrimary8(s, d, n, ra);
      b.shadePrimary8(s, d, n, rb);
      for (int k = 0; k < n; ++k) {
        ASSERT_EQ(ra[k].x, rb[k].x) << "block " << block << " lane " << k;
        ASSERT_EQ(ra[k].y, rb[k].y);
        ASSERT_EQ(ra[k].z, rb[k].z);
        lit += luminance(ra[k]) > 0.0f;
      }
    }
  }
  EXPECT_GT(lit, 100);
  PathTracer pa(rt, scene, grid, PathSettings{}), pb(rt, scene, plain, PathSettings{});
  for (uint32_t i = 0; i < 256; ++i) {
    const Vec3 dir = normalize(Vec3(u(rng) - 0.5f, u(rng) - 0.6f, -1.0f));
    SobolSampler sa(1, i, 0), sb(1, i, 0);
    const Vec3 la = pa.radiance(eye, dir, 0.0f, sa), lb = pb.radiance(eye, dir, 0.0f, sb);
    ASSERT_EQ(la.x, lb.x) << "path " << i;
    ASSERT_EQ(la.y, lb.y);
    ASSERT_EQ(la.z, lb.z);
  }
}
