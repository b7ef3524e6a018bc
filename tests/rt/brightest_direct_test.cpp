// DiffuseGI::brightestDirect (the direct_light pass): the `count` lights that give a point the
// most unshadowed light, each with its shadow ray; brightestDirect8 traces eight points' rays as
// packets and must give each point what brightestDirect gives it.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>

#include "rt/diffuse_gi.h"
#include "rt/ray_tracer.h"
#include "scene/primitives.h"
#include "scene/scene.h"
#include "shading/surface_resolve.h"

using namespace tandem;

namespace {

// A grey floor under a row of 12 point lamps 1 m up (4 m range) and a dim sun, with thin posts
// between lamps and floor: some points see a lamp, their neighbours do not.
Scene postsUnderLamps(bool posts) {
  Scene s;
  Material grey;
  grey.diffuse = {0.5f, 0.5f, 0.5f};
  const int mat = s.addMaterial(grey);
  Transform floor;
  floor.scale = {10, 1, 10};
  s.addObject("floor", s.addMesh(makePlane(4)), mat, floor);
  const int cube = s.addMesh(makeCube());
  for (int i = 0; posts && i < 12; ++i) {
    Transform post;
    post.position = {-6.3f + 1.1f * float(i), 0.4f, 0.3f};
    post.scale = {0.08f, 0.4f, 0.08f};
    s.addObject("post" + std::to_string(i), cube, mat, post);
  }
  for (int i = 0; i < 12; ++i) {
    Light l;
    l.type = LightType::Point;
    l.position = {-6.0f + 1.1f * float(i), 1.0f, 0.0f};
    l.intensity = 0.4f + 0.15f * float(i % 4);
    l.range = 4.0f;
    s.lights.push_back(l);
  }
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = normalize(Vec3(0.3f, -1.0f, 0.2f));
  sun.intensity = 0.05f;
  s.lights.push_back(sun);
  return s;
}

// Floor surfaces at `count` random points seen from above, in clusters of 8 within `spread`
// metres (as neighbouring pixels are: brightestDirect8 leaves out the lights too far from all
// eight to rank).
std::vector<SurfaceSample> floorPoints(const FrameScene& fs, const RayTracer& rt, int count,
                                       std::vector<Vec3>& wo, float spread = 20.0f) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> x(-7.0f, 7.0f), z(-2.0f, 2.0f), near(-0.5f, 0.5f);
  std::vector<SurfaceSample> out;
  Vec3 centre;
  while (int(out.size()) < count) {
    if (out.size() % 8 == 0) centre = {x(rng), 0.0f, z(rng)};
    Ray r;
    r.origin = {std::clamp(centre.x + spread * near(rng), -7.0f, 7.0f), 3.0f,
                std::clamp(centre.z + spread * near(rng), -2.0f, 2.0f)};
    r.dir = normalize(Vec3(0.05f, -1.0f, 0.1f));
    const Hit h = rt.intersect(r);
    if (!h.valid() || h.object != 0) continue;  // the floor only
    const float tuv[3] = {h.t, h.u, h.v};
    out.push_back(resolveSurface(fs, h.object, h.prim, r.origin, r.dir, 0.0f, tuv));
    wo.push_back(-r.dir);
  }
  return out;
}

// A scene made ready to trace, with its direct-light estimator.
struct Traced {
  explicit Traced(Scene scene) : s(std::move(scene)), shading(ShadingContext::from(s)) {
    fs.update(s, 0, 0);
    rt.update(fs);
  }
  Scene s;
  FrameScene fs;
  RayTracer rt;
  ShadingContext shading;
  DiffuseGI gi{rt, s, shading};
};

}  // namespace

// Packets or single rays, every point gets the same light, bit for bit, for any count of lights,
// from points far apart or close together, and some points are shadowed from some of their
// lights (the rays decide something).
TEST(BrightestDirect, PacketsGiveWhatSingleRaysGive) {
  const Traced t(postsUnderLamps(true));
  const FrameScene& fs = t.fs;
  const RayTracer& rt = t.rt;
  const ShadingContext& shading = t.shading;
  const DiffuseGI& gi = t.gi;
  for (const float spread : {20.0f, 0.3f}) {
    std::vector<Vec3> wo;
    const std::vector<SurfaceSample> pts = floorPoints(fs, rt, 203, wo, spread);  // not 8 x n
    int darker = 0;
    for (const int count : {0, 1, 3, 13}) {
      uint64_t singleRays = 0, packetRays = 0;
      for (size_t b = 0; b < pts.size(); b += 8) {
        const int n = int(std::min<size_t>(8, pts.size() - b));
        Vec3 packet[8];
        gi.brightestDirect8(&pts[b], &wo[b], n, count, 0.0f, packet, packetRays);
        for (int j = 0; j < n; ++j) {
          const Vec3 single =
              gi.brightestDirect(pts[b + size_t(j)], wo[b + size_t(j)], count, 0.0f, singleRays);
          EXPECT_EQ(packet[j].x, single.x) << count << " " << b + size_t(j);
          EXPECT_EQ(packet[j].y, single.y);
          EXPECT_EQ(packet[j].z, single.z);
          // Against every light unshadowed: the posts take some away.
          if (count == 13) {
            Vec3 all(0.0f);
            for (const PreparedLight& l : shading.lights) {
              const LightSample ls = sampleLight(l, pts[b + size_t(j)].position);
              all += ls.radiance * (std::max(ls.wi.y, 0.0f) / kPi);
            }
            EXPECT_LE(single.x, all.x * 1.0001f + 1e-7f);
            darker += single.x < 0.99f * all.x ? 1 : 0;
          }
        }
      }
      EXPECT_EQ(packetRays, singleRays) << count;
      if (count > 0) {
        EXPECT_GT(singleRays, 0u);
      }
    }
    EXPECT_GT(darker, 10) << spread;
    EXPECT_LT(darker, 193) << spread;
  }
}

// With nothing in the way and one light asked for, a point gets exactly its brightest light's
// share; with every light, all of them.
TEST(BrightestDirect, TakesTheBrightestLightsFirst) {
  const Traced t(postsUnderLamps(false));
  const FrameScene& fs = t.fs;
  const RayTracer& rt = t.rt;
  const ShadingContext& shading = t.shading;
  const DiffuseGI& gi = t.gi;
  std::vector<Vec3> wo;
  const std::vector<SurfaceSample> pts = floorPoints(fs, rt, 40, wo);
  uint64_t rays = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    float best = 0, all = 0;
    for (const PreparedLight& l : shading.lights) {
      const LightSample ls = sampleLight(l, pts[i].position);
      const float e = ls.radiance.x * std::max(ls.wi.y, 0.0f) / kPi;
      best = std::max(best, e);
      all += e;
    }
    ASSERT_GT(best, 0.0f);
    EXPECT_NEAR(gi.brightestDirect(pts[i], wo[i], 1, 0.0f, rays).x, best, 1e-5f * best) << i;
    EXPECT_NEAR(gi.brightestDirect(pts[i], wo[i], 64, 0.0f, rays).x, all, 1e-5f * all) << i;
  }
}
