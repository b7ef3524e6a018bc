// The GPU's BVH and closest-hit kernel against Embree (RayTracer::intersect) on the built-in
// scenes: camera rays through every pixel of a small frame and random rays from inside the scene.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "gpu/gpu_bvh.h"
#include "gpu/gpu_test_util.h"
#include "gpu/gpu_tracer.h"
#include "rt/ray_tracer.h"
#include "scene/camera.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

namespace tandem {
namespace {

// Every item lands in exactly one leaf, and every node's box holds its children's or items'.
TEST(GpuBvh, LeavesCoverEveryItemOnceInsideTheirBoxes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-10, 10);
  std::vector<Bounds3> boxes(1000);
  for (Bounds3& b : boxes) {
    const Vec3 c{u(rng), u(rng), u(rng)};
    b.extend(c);
    b.extend(c + Vec3(0.3f, 0.1f, 0.2f));
  }
  const BvhBuild bvh = buildBvh(boxes);
  std::vector<int> seen(boxes.size(), 0);
  auto inside = [](const BvhNode& n, const Bounds3& b) {
    return b.lo.x >= n.lox && b.lo.y >= n.loy && b.lo.z >= n.loz && b.hi.x <= n.hix &&
           b.hi.y <= n.hiy && b.hi.z <= n.hiz;
  };
  for (const BvhNode& n : bvh.nodes) {
    if (n.lox > n.hix) continue;  // an empty slot
    if (n.count == 0) {
      ASSERT_LT(n.a + 1, bvh.nodes.size());
      for (int c = 0; c < 2; ++c) {
        const BvhNode& k = bvh.nodes[n.a + uint32_t(c)];
        if (k.lox > k.hix) continue;
        EXPECT_TRUE(inside(n, {{k.lox, k.loy, k.loz}, {k.hix, k.hiy, k.hiz}}));
      }
    } else {
      EXPECT_LE(n.count, 4u);
      for (uint32_t i = n.a; i < n.a + n.count; ++i) {
        ++seen[bvh.items[i]];
        EXPECT_TRUE(inside(n, boxes[bvh.items[i]]));
      }
    }
  }
  for (const int s : seen) EXPECT_EQ(s, 1);
}

// Camera rays through every pixel of a 96 x 54 frame and 4,000 random rays from inside the scene.
std::vector<Ray> testRays(const Scene& scene, std::mt19937& rng) {
  std::vector<Ray> rays;
  const Camera cam = Camera::make(defaultCamera(scene), 96, 54);
  for (int y = 0; y < 54; ++y)
    for (int x = 0; x < 96; ++x) {
      Ray r;
      cam.generateRay(float(x) + 0.5f, float(y) + 0.5f, r.origin, r.dir);
      rays.push_back(r);
    }
  const Bounds3 b = scene.bounds();
  std::uniform_real_distribution<float> u(0, 1), n(-1, 1);
  for (int i = 0; i < 4000; ++i) {
    Ray r;
    r.origin = {b.lo.x + (b.hi.x - b.lo.x) * u(rng), b.lo.y + (b.hi.y - b.lo.y) * u(rng),
                b.lo.z + (b.hi.z - b.lo.z) * u(rng)};
    r.dir = normalize(Vec3{n(rng), n(rng), n(rng)} + Vec3(1e-4f));
    r.tnear = 1e-4f;
    rays.push_back(r);
  }
  return rays;
}

// The GPU's answers against Embree's for the frame `fs` (RayTracer built for it): hit or miss
// and the distance (1e-4 relative) agree for all but 1 ray in 2,000 (grazing an edge), the same
// triangle for all but ties (0.5 %: another triangle at the same distance), on the same triangle
// the same barycentrics (1e-3); occlusion of segments ending short of or past the first surface
// agrees for all but 1 in 2,000 (one ending on a surface).
void expectAgreement(const std::string& name, const Scene& scene, const FrameScene& fs,
                     GpuTracer& gpu) {
  RayTracer cpu;
  cpu.update(fs);
  gpu.update(fs);
  std::mt19937 rng(11);
  std::vector<Ray> rays = testRays(scene, rng);
  std::vector<GpuRay> gr;
  for (const Ray& r : rays)
    gr.push_back({r.origin.x, r.origin.y, r.origin.z, r.tnear, r.dir.x, r.dir.y, r.dir.z, r.tfar});
  const std::vector<GpuHit> hits = gpu.closest(gr);
  ASSERT_EQ(hits.size(), rays.size());
  int hitMiss = 0, farther = 0, hitCount = 0, ties = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Hit h = cpu.intersect(rays[i]);
    const GpuHit& g = hits[i];
    hitCount += h.valid();
    if (h.valid() != (g.object >= 0)) {
      ++hitMiss;
      continue;
    }
    if (!h.valid()) continue;
    if (std::abs(g.t - h.t) > 1e-4f * std::max(1.0f, h.t)) {
      ++farther;
      continue;
    }
    if (h.object != g.object || h.prim != g.prim) {
      ++ties;
      continue;
    }
    EXPECT_NEAR(g.u, h.u, 1e-3f) << name << " ray " << i;
    EXPECT_NEAR(g.v, h.v, 1e-3f) << name << " ray " << i;
  }
  EXPECT_GT(hitCount, int(rays.size()) / 2) << name;  // the rays see the scene
  EXPECT_LE(hitMiss, int(rays.size()) / 2000) << name;
  EXPECT_LE(farther, int(rays.size()) / 2000) << name;
  EXPECT_LE(ties, int(rays.size()) / 200) << name;

  std::uniform_real_distribution<float> reach(0.05f, 2.0f);
  for (size_t i = 0; i < rays.size(); ++i) {
    rays[i].tfar = (hits[i].object >= 0 ? hits[i].t : 10.0f) * reach(rng);
    gr[i].tfar = rays[i].tfar;
  }
  const std::vector<uint8_t> occ = gpu.occluded(gr);
  int disagree = 0, blocked = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const bool o = cpu.occluded(rays[i]);
    blocked += o;
    disagree += o != (occ[i] != 0);
  }
  EXPECT_GT(blocked, int(rays.size()) / 4) << name;
  EXPECT_LT(blocked, int(rays.size()) * 3 / 4) << name;
  EXPECT_LE(disagree, int(rays.size()) / 2000) << name;
  std::printf(
      "%s: %zu rays, %d hit, %d hit/miss, %d at another distance, %d ties; %d of %zu "
      "segments occluded, %d disagree\n",
      name.c_str(), rays.size(), hitCount, hitMiss, farther, ties, blocked, rays.size(), disagree);
}

TEST(GpuTrace, MatchesEmbreeOnTheBuiltInScenes) {
  REQUIRE_GPU(dev);
  for (const char* name : {"cornell", "spheres", "atrium"}) {
    const Scene scene = loadScene(name);
    FrameScene fs;
    fs.update(scene, 0.0f, 0.0f);
    GpuTracer gpu(dev);
    expectAgreement(name, scene, fs, gpu);
  }
  expectNoValidationMessages(*dev);
}

// Objects that move between frames: their BVHs refitted where they now are, still Embree's hits.
TEST(GpuTrace, RefitsWhatMoves) {
  REQUIRE_GPU(dev);
  const Scene scene =
      loadScene(std::string(TANDEM_SOURCE_DIR) + "/scenes/cornell_motion_blur.json");
  FrameScene fs;
  GpuTracer gpu(dev);
  fs.update(scene, 0.0f, 0.0f);
  expectAgreement("frame 0", scene, fs, gpu);
  bool moved = false;
  for (const float t : {0.5f, 1.0f}) {
    fs.update(scene, t, t - 0.5f);
    for (const FrameObject& o : fs.objects) moved |= o.moved;
    expectAgreement("t = " + std::to_string(t), scene, fs, gpu);
  }
  EXPECT_TRUE(moved) << "the scene's objects should move";
  expectNoValidationMessages(*dev);
}

}  // namespace
}  // namespace tandem
