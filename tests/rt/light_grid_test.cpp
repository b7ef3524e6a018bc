// Light selection by grid (rt/light_grid.h): a distribution per cell that picks what it reports,
// never drops a light that can reach the point, prefers near lights, and leaves the diffuse-GI
// estimator unbiased while lowering its variance among many lights.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rt/diffuse_gi.h"
#include "rt/ray_tracer.h"
#include "rt/sampler.h"
#include "scene/primitives.h"
#include "scene/scene.h"
#include "shading/surface_resolve.h"

using namespace tandem;

namespace {

// A 20 x 20 m grey floor at y = 0 under a black sky, lit by a row of 16 point lights 0.5 m above
// it, 1.2 m apart, each reaching 4 m (range), plus a dim sun: the light at a floor point comes
// from a few nearby lamps, as in the forest scene.
Scene lampRow() {
  Scene s;
  Material grey;
  grey.diffuse = {0.5f, 0.5f, 0.5f};
  Transform xf;
  xf.scale = {20, 1, 20};
  s.addObject("floor", s.addMesh(makePlane(4)), s.addMaterial(grey), xf);
  for (int i = 0; i < 16; ++i) {
    Light l;
    l.type = LightType::Point;
    l.position = {-9.0f + 1.2f * float(i), 0.5f, 0.0f};
    l.intensity = 0.5f + 0.1f * float(i % 3);
    l.range = 4.0f;
    s.lights.push_back(l);
  }
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = normalize(Vec3(0.2f, -1.0f, 0.1f));
  sun.intensity = 0.05f;
  s.lights.push_back(sun);
  s.skybox.color = {0, 0, 0};
  s.ambient = {0, 0, 0};
  return s;
}

}  // namespace

// At any point the candidates' probabilities add to 1, pick() reports the probability of what
// it picked, and a sweep of u picks each light as often as its probability says.
TEST(LightGrid, PicksWhatItReportsWithItsProbability) {
  const Scene s = lampRow();
  const ShadingContext shading = ShadingContext::from(s);
  const LightGrid grid = DiffuseGI::buildGrid(s, shading);
  ASSERT_EQ(grid.candidateCount(), s.lights.size());
  EXPECT_GT(grid.cells(0), 8);
  std::mt19937 g(5);
  std::uniform_real_distribution<float> coord(-10.0f, 10.0f);
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3 p(coord(g), 0.0f, coord(g));
    double total = 0;
    for (size_t i = 0; i < s.lights.size(); ++i) total += grid.probability(p, int(i));
    EXPECT_NEAR(total, 1.0, 1e-5) << trial;
    const int n = 20000;
    std::vector<int> counts(s.lights.size(), 0);
    for (int k = 0; k < n; ++k) {
      const LightGrid::Pick pick = grid.pick(p, (float(k) + 0.5f) / float(n));
      ASSERT_GE(pick.light, 0);
      ASSERT_GT(pick.pdf, 0.0f);
      EXPECT_FLOAT_EQ(pick.pdf, grid.probability(p, pick.light));
      ++counts[size_t(pick.light)];
    }
    for (size_t i = 0; i < s.lights.size(); ++i)
      EXPECT_NEAR(double(counts[i]) / n, grid.probability(p, int(i)), 2.0 / n) << trial << " " << i;
  }
}

// A lamp out of range of the point's cell is never picked; one in range always can be; the
// nearest lamp is the likeliest; the sun (everywhere) keeps a probability.
TEST(LightGrid, KeepsEveryLightThatCanReachAndPrefersNearOnes) {
  const Scene s = lampRow();
  const ShadingContext shading = ShadingContext::from(s);
  const LightGrid grid = DiffuseGI::buildGrid(s, shading);
  const Vec3 p(-9.0f, 0.0f, 0.3f);           // beside lamp 0
  EXPECT_EQ(grid.probability(p, 15), 0.0f);  // 18 m away, range 4
  for (int i = 0; i <= 2; ++i) EXPECT_GT(grid.probability(p, i), 0.0f) << i;
  EXPECT_GT(grid.probability(p, 16), 0.0f);  // the sun
  EXPECT_GT(grid.probability(p, 0), grid.probability(p, 2));
  EXPECT_GT(grid.probability(p, 0), 1.0f / 17.0f);
  // Points far outside the bounds use the nearest cell: still a distribution.
  double total = 0;
  for (int i = 0; i < 17; ++i) total += grid.probability(Vec3(100, 50, -100), i);
  EXPECT_NEAR(total, 1.0, 1e-5);
}

// The diffuse-GI estimate on the floor (the bounce only sees the black sky) converges to the
// exact radiance albedo / π x Σ irradiance with either selection, and the grid's (visibility
// probed) variance is several times lower among these 17 lights.
TEST(LightGrid, DiffuseGIStaysUnbiasedWithLessVariance) {
  const Scene s = lampRow();
  FrameScene fs;
  fs.update(s, 0, 0);
  RayTracer rt;
  rt.update(fs);
  const ShadingContext shading = ShadingContext::from(s);
  const LightGrid grid = DiffuseGI::buildGrid(s, shading, &rt);
  ASSERT_GT(grid.probeRays(), 0u);
  const DiffuseGI uniform(rt, s, shading), byGrid(rt, s, shading, &grid);
  for (const Vec3 p : {Vec3(-8.7f, 0.0f, 0.4f), Vec3(0.3f, 0.0f, -1.1f), Vec3(6.0f, 0.0f, 2.5f)}) {
    const Vec3 o = p + Vec3(0.0f, 2.0f, 0.5f), d = normalize(p - o);
    Ray r;
    r.origin = o;
    r.dir = d;
    const Hit h = rt.intersect(r);
    ASSERT_TRUE(h.valid());
    const float tuv[3] = {h.t, h.u, h.v};
    const SurfaceSample sf = resolveSurface(fs, h.object, h.prim, o, d, 0.0f, tuv);
    double exact = 0;
    for (const PreparedLight& l : shading.lights) {
      const LightSample ls = sampleLight(l, sf.position);
      exact += 0.5 / kPi * ls.radiance.x * std::max(ls.wi.y, 0.0f);
    }
    ASSERT_GT(exact, 0.0);
    double mean[2] = {0, 0}, var[2] = {0, 0};
    const int n = 4096;
    uint64_t rays = 0;
    for (int k = 0; k < 2; ++k) {
      const DiffuseGI& gi = k == 0 ? uniform : byGrid;
      double sum = 0, sum2 = 0;
      for (int i = 0; i < n; ++i) {
        SobolSampler rng(7, 1, uint32_t(i));
        const double v = gi.radiance(sf, -d, rng, 0.0f, rays).x;
        sum += v;
        sum2 += v * v;
      }
      mean[k] = sum / n;
      var[k] = sum2 / n - mean[k] * mean[k];
      EXPECT_NEAR(mean[k] / exact, 1.0, 0.02) << k << " at " << p.x;
    }
    EXPECT_LT(var[1], 0.25 * var[0]) << p.x;
  }
}

// The visibility probe: behind a wall that hides lamp A from the right half of the floor, the
// grid picks A there far less often than without the probe, but never never (unbiased), and
// picks the visible lamp B more.
TEST(LightGrid, VisibilityProbeAvoidsHiddenLights) {
  Scene s;
  Material grey;
  grey.diffuse = {0.5f, 0.5f, 0.5f};
  const int mat = s.addMaterial(grey);
  Transform floor;
  floor.scale = {6, 1, 6};
  s.addObject("floor", s.addMesh(makePlane(4)), mat, floor);
  Transform wall;  // x = 0, 3 m tall, across the whole floor
  wall.position = {0.0f, 1.5f, 0.0f};
  wall.scale = {0.05f, 1.5f, 6.0f};
  s.addObject("wall", s.addMesh(makeCube()), mat, wall);
  for (float x : {-2.0f, 2.0f}) {
    Light l;
    l.type = LightType::Point;
    l.position = {x, 1.0f, 0.0f};
    l.intensity = 1.0f;
    s.lights.push_back(l);
  }
  FrameScene fs;
  fs.update(s, 0, 0);
  RayTracer rt;
  rt.update(fs);
  const ShadingContext shading = ShadingContext::from(s);
  const LightGrid blind = DiffuseGI::buildGrid(s, shading);
  const LightGrid probed = DiffuseGI::buildGrid(s, shading, &rt);
  ASSERT_GT(probed.probeRays(), 0u);
  const Vec3 p(3.5f, 0.0f, 1.0f);  // right of the wall: lamp 0 (x = -2) is hidden
  EXPECT_GT(blind.probability(p, 0), 0.1f);
  EXPECT_LT(probed.probability(p, 0), 0.5f * blind.probability(p, 0));
  EXPECT_GT(probed.probability(p, 0), 0.0f);
  EXPECT_GT(probed.probability(p, 1), blind.probability(p, 1));
}
