#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cstring>

#include "raster/rasterizer.h"
#include "scene/builtin_scenes.h"
#include "scene/primitives.h"
#include "test_util.h"

using namespace tandem;

namespace {

// One object per triangle so coverage of each can be told apart.
Scene trianglesScene(const std::vector<std::array<Vec3, 3>>& tris, bool doubleSided = false) {
  Scene s;
  Material m;
  m.doubleSided = doubleSided;
  int mat = s.addMaterial(m);
  for (size_t i = 0; i < tris.size(); ++i) {
    Mesh mesh;
    mesh.positions = {tris[i][0], tris[i][1], tris[i][2]};
    mesh.indices = {0, 1, 2};
    s.addObject("t" + std::to_string(i), s.addMesh(mesh), mat);
  }
  return s;
}

// Orthographic camera looking down -Z whose pixel centres sit on integer world coordinates:
// a 16 x 16 view of [-8, 8]^2 has pixel (i, j) centred at x = i - 7.5, y = 7.5 - j.
CameraDesc orthoCamera() {
  CameraDesc c;
  c.projection = Projection::Orthographic;
  c.position = {0, 0, 5};
  c.lookAt = {0, 0, 0};
  c.orthoHeight = 16;
  c.nearPlane = 0.1f;
  c.farPlane = 100;
  return c;
}

VisibilityBuffer rasterize(const Scene& s, const CameraDesc& cd, int w, int h) {
  FrameScene fs;
  fs.update(s, 0, 0);
  Camera cam = Camera::make(cd, w, h);
  Rasterizer r;
  VisibilityBuffer vb;
  r.render(fs, cam, vb);
  return vb;
}

}  // namespace

// Two triangles sharing a diagonal edge that passes exactly through pixel centres: every pixel
// centre in the square is drawn by exactly one of them (top-left rule), none twice, no holes.
TEST(Rasterizer, SharedEdgeCoveredExactlyOnce) {
  // Corners on pixel centres: (-6.5, -6.5) .. (5.5, 5.5); the diagonal hits centres exactly.
  Vec3 a{-6.5f, -6.5f, 0}, b{5.5f, -6.5f, 0}, c{5.5f, 5.5f, 0}, d{-6.5f, 5.5f, 0};
  Scene first = trianglesScene({{a, b, c}}), second = trianglesScene({{a, c, d}});
  VisibilityBuffer v1 = rasterize(first, orthoCamera(), 16, 16),
                   v2 = rasterize(second, orthoCamera(), 16, 16);
  int both = 0, covered = 0;
  for (size_t i = 0; i < v1.object.size(); ++i) {
    bool c1 = v1.object[i] != kNoObject, c2 = v2.object[i] != kNoObject;
    both += c1 && c2;
    covered += c1 || c2;
  }
  EXPECT_EQ(both, 0);
  // Centres inside the closed square: 13 x 13, minus the square's right and top edges, which
  // belong to neighbours (by the same rule): 12 x 12 drawn here... plus edges owned by these.
  EXPECT_GE(covered, 12 * 12);
  EXPECT_LE(covered, 13 * 13);
}

// Fans of triangles around a shared vertex tile a square without gaps or double coverage.
TEST(Rasterizer, FanWithoutGapsOrOverlap) {
  std::vector<std::array<Vec3, 3>> tris;
  Vec3 centre{0.5f, -0.5f, 0};
  const int n = 12;
  for (int i = 0; i < n; ++i) {
    float a0 = 2 * kPi * i / n, a1 = 2 * kPi * (i + 1) / n;
    tris.push_back({centre, centre + Vec3(std::cos(a0), std::sin(a0), 0) * 6.3f,
                    centre + Vec3(std::cos(a1), std::sin(a1), 0) * 6.3f});
  }
  std::vector<int> count(256, 0);
  for (auto& t : tris) {
    VisibilityBuffer v = rasterize(trianglesScene({t}), orthoCamera(), 16, 16);
    for (size_t i = 0; i < 256; ++i) count[i] += v.object[i] != kNoObject;
  }
  // The inscribed disc of radius 6.3 cos(15 deg) ~ 6.08 must be covered exactly once.
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) {
      Vec3 p{i - 7.5f, 7.5f - j, 0};
      float r = length(p - centre);
      if (r < 6.0f) {
        EXPECT_EQ(count[j * 16 + i], 1) << "pixel " << i << "," << j;
      }
      EXPECT_LE(count[j * 16 + i], 1);
    }
}

TEST(Rasterizer, BackFacesCulledUnlessDoubleSided) {
  // Clockwise as seen from the camera (+Z): a back face.
  std::array<Vec3, 3> cw = {Vec3(-4, -4, 0), Vec3(-4, 4, 0), Vec3(4, -4, 0)};
  VisibilityBuffer single = rasterize(trianglesScene({cw}, false), orthoCamera(), 16, 16);
  VisibilityBuffer both = rasterize(trianglesScene({cw}, true), orthoCamera(), 16, 16);
  size_t a = std::count_if(single.object.begin(), single.object.end(),
                           [](uint32_t o) { return o != kNoObject; });
  size_t b = std::count_if(both.object.begin(), both.object.end(),
                           [](uint32_t o) { return o != kNoObject; });
  EXPECT_EQ(a, 0u);
  EXPECT_GT(b, 20u);
}

TEST(Rasterizer, NearerTriangleWinsReversedZ) {
  std::array<Vec3, 3> far = {Vec3(-6, -6, -1), Vec3(6, -6, -1), Vec3(0, 6, -1)};
  std::array<Vec3, 3> near = {Vec3(-6, -6, 1), Vec3(6, -6, 1), Vec3(0, 6, 1)};
  for (bool nearFirst : {false, true}) {
    Scene s = nearFirst ? trianglesScene({near, far}) : trianglesScene({far, near});
    VisibilityBuffer v = rasterize(s, orthoCamera(), 16, 16);
    uint32_t nearId = nearFirst ? 0 : 1;
    EXPECT_EQ(v.object[8 * 16 + 8], nearId);
    EXPECT_GT(v.depth[8 * 16 + 8], 0.0f);
  }
}

TEST(Rasterizer, AlphaMaskDiscardsTransparentTexels) {
  Scene s;
  Texture t;
  t.texels = Buffer(2, 1, 4, 1.0f);
  t.texels.at(1, 0)[3] = 0.0f;  // right half transparent
  t.wrapS = t.wrapT = WrapMode::ClampToEdge;
  Material m;
  m.alphaMode = AlphaMode::Mask;
  m.diffuseTexture = s.addTexture(t);
  Mesh plane = makePlane(1);  // XZ plane, UV u along +X
  int mat = s.addMaterial(m);
  s.addObject("p", s.addMesh(plane), mat, Transform{{0, 0, 0}, {90, 0, 0}, {6, 1, 6}});
  VisibilityBuffer v = rasterize(s, orthoCamera(), 16, 16);
  // Left part (u < 0.5, texel alpha ~1 after bilinear) drawn, right part discarded.
  EXPECT_NE(v.object[8 * 16 + 3], kNoObject);
  EXPECT_EQ(v.object[8 * 16 + 12], kNoObject);
}

TEST(Rasterizer, DeterministicAcrossRuns) {
  Scene s = makeSpheresScene();
  VisibilityBuffer a = rasterize(s, s.camera, 200, 120), b = rasterize(s, s.camera, 200, 120);
  EXPECT_EQ(a.object, b.object);
  EXPECT_EQ(a.prim, b.prim);
  EXPECT_EQ(a.depth, b.depth);
}

// Per-object frustum culling: an object wholly behind the camera or beside the view is skipped
// before its vertices are transformed (counted as culled), and the picture is unchanged.
TEST(Rasterizer, ObjectsOutsideTheFrustumAreCulledWhole) {
  const std::array<Vec3, 3> inView = {Vec3{-4, -4, 0}, Vec3{4, -4, 0}, Vec3{0, 4, 0}};
  const std::array<Vec3, 3> behind = {Vec3{-4, -4, 9}, Vec3{4, -4, 9}, Vec3{0, 4, 9}};
  const std::array<Vec3, 3> beside = {Vec3{20, -4, 0}, Vec3{28, -4, 0}, Vec3{24, 4, 0}};
  Scene alone = trianglesScene({inView}), crowd = trianglesScene({inView, behind, beside});
  FrameScene fs;
  fs.update(crowd, 0, 0);
  Camera cam = Camera::make(orthoCamera(), 16, 16);
  Rasterizer r;
  VisibilityBuffer vb;
  RasterStats stats;
  r.render(fs, cam, vb, &stats);
  EXPECT_EQ(stats.trianglesIn, 3u);
  EXPECT_EQ(stats.trianglesCulled, 2u);
  EXPECT_EQ(stats.trianglesBinned, 1u);
  VisibilityBuffer ref = rasterize(alone, orthoCamera(), 16, 16);
  EXPECT_EQ(vb.object, ref.object);
  EXPECT_EQ(vb.depth, ref.depth);
}

// Clip-space vertices are reused while neither camera nor geometry changes, and recomputed when
// either does: a static camera must still see an object that moved.
TEST(Rasterizer, CachedVerticesFollowMovingObjectsAndCameras) {
  Scene s = trianglesScene({{Vec3{-4, -4, 0}, Vec3{4, -4, 0}, Vec3{0, 4, 0}}});
  FrameScene fs;
  fs.update(s, 0, 0);
  Camera cam = Camera::make(orthoCamera(), 16, 16);
  Rasterizer r;
  VisibilityBuffer first, again, moved, panned;
  r.render(fs, cam, first);
  r.render(fs, cam, again);
  EXPECT_EQ(first.object, again.object);
  s.objects[0].local.position = {3, 0, 0};
  fs.update(s, 1, 0);
  r.render(fs, cam, moved);
  EXPECT_NE(first.object, moved.object);
  EXPECT_EQ(moved.object, rasterize(s, orthoCamera(), 16, 16).object);
  CameraDesc side = orthoCamera();
  side.position.x = side.lookAt.x = -3;
  r.render(fs, Camera::make(side, 16, 16), panned);
  EXPECT_EQ(panned.object, rasterize(s, side, 16, 16).object);
  EXPECT_NE(panned.object, moved.object);
}

// The tile loop is a Highway kernel dispatched at run time: every instruction set this machine
// runs (AVX-512, AVX2, SSE4, the baseline; 8, 4, 2 and 1 edge lanes) draws the same visibility
// buffer bit for bit, with triangles large (the floor, walls) and small (the columns' detail),
// and a width whose last tile is narrower than a vector.
TEST(Rasterizer, EveryInstructionSetDrawsTheSameVisibility) {
  const Scene scene = makeAtriumScene();
  CameraDesc cd = scene.camera;
  const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  std::vector<VisibilityBuffer> out;
  for (int64_t target : targets) {
    hwy::SetSupportedTargetsForTest(target);
    out.push_back(rasterize(scene, cd, 197, 111));
  }
  hwy::SetSupportedTargetsForTest(0);
  size_t covered = 0;
  for (uint32_t o : out[0].object) covered += o != kNoObject;
  EXPECT_GT(covered, out[0].object.size() / 2);
  for (size_t t = 1; t < out.size(); ++t) {
    EXPECT_EQ(out[t].object, out[0].object) << hwy::TargetName(targets[t]);
    EXPECT_EQ(out[t].prim, out[0].prim) << hwy::TargetName(targets[t]);
    EXPECT_EQ(0, std::memcmp(out[t].depth.data(), out[0].depth.data(),
                             out[0].depth.size() * sizeof(float)))
        << hwy::TargetName(targets[t]);
  }
}
