// Raster and ray-traced G-buffers of the same frame agree on object id and depth on all but a
// thin band of edge pixels.
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cstring>

#include "raster/gbuffer.h"
#include "scene/builtin_scenes.h"
#include "scene/loaders.h"
#include "test_util.h"

using namespace tandem;

namespace {

struct Agreement {
  size_t covered = 0, idMismatch = 0, idMismatchInterior = 0, depthChecked = 0, depthBad = 0;
  float maxRel = 0;
  size_t attrBad = 0;  // pixels whose shading attributes (normal, diffuse, uv-dependent) differ
};

// A pixel is on an edge when any 8-neighbour of the raster id differs from it.
Agreement compareGBuffers(const Scene& scene, const CameraDesc& cam, int w, int h,
                          Vec2 jitter = {0, 0}) {
  auto raster = test::renderOnce(scene, "deferred", w, h, cam, jitter);
  auto rt = test::renderOnce(scene, "deferred-rt-gbuffer", w, h, cam, jitter);
  const Buffer& idA = raster->context().input("object_id");
  const Buffer& idB = rt->context().input("object_id");
  const Buffer& dA = raster->context().input("depth");
  const Buffer& dB = rt->context().input("depth");
  Agreement a;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float id = idA.at(x, y)[0];
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          int xx = std::clamp(x + dx, 0, w - 1), yy = std::clamp(y + dy, 0, h - 1);
          if (idA.at(xx, yy)[0] != id) edge = true;
        }
      if (id >= 0) ++a.covered;
      if (id != idB.at(x, y)[0]) {
        ++a.idMismatch;
        if (!edge) ++a.idMismatchInterior;
        continue;
      }
      if (id < 0) continue;
      ++a.depthChecked;
      float za = dA.at(x, y)[0], zb = dB.at(x, y)[0];
      float rel = std::abs(za - zb) / std::max(za, zb);
      a.maxRel = std::max(a.maxRel, rel);
      if (rel > 1e-4f) ++a.depthBad;
      // Same triangle, same resolve code: attributes agree up to the rounding of the two ways
      // to get barycentrics (raster: per-triangle planes; rays: Moller-Trumbore), both of which
      // cancel terms |eye - vertex| / |edge| times larger than the result: ~1e-5 in u for 1 cm
      // triangles 10 m away, so 1e-3 in a normal or a texel-blended colour.
      Vec3 nA = raster->context().input("normal").rgb(x, y),
           nB = rt->context().input("normal").rgb(x, y);
      Vec3 cA = raster->context().input("diffuse").rgb(x, y),
           cB = rt->context().input("diffuse").rgb(x, y);
      if (length(nA - nB) > 1e-3f || length(cA - cB) > 1e-3f) ++a.attrBad;
    }
  return a;
}

void expectAgreement(const Agreement& a, size_t pixels) {
  EXPECT_GT(a.covered, pixels / 10) << "image nearly empty";
  // Tolerances: at most 1% of pixels may differ in id, none of them away from an edge;
  // depth agrees to 1e-4 relative on all but 0.1% of the pixels where ids agree.
  EXPECT_LE(a.idMismatch, pixels / 100) << a.idMismatch << " id mismatches";
  EXPECT_EQ(a.idMismatchInterior, 0u);
  // Attributes: the two may pick neighbouring triangles of one object on a crease (a cube's edge),
  // so allow 0.2% of pixels; everywhere else normal and diffuse match to 1e-3.
  EXPECT_LE(a.attrBad, a.depthChecked / 500 + 1)
      << a.attrBad << " of " << a.depthChecked
      << " pixels with the same id differ in normal or diffuse";
  EXPECT_LE(a.depthBad, a.depthChecked / 1000 + 1)
      << a.depthBad << " depth mismatches, max relative " << a.maxRel;
}

}  // namespace

class GBufferAgreement : public ::testing::TestWithParam<std::string> {};

TEST_P(GBufferAgreement, RasterMatchesRayTraced) {
  Scene s = makeBuiltinScene(GetParam());
  const int w = 320, h = 180;
  expectAgreement(compareGBuffers(s, s.camera, w, h), size_t(w) * h);
}

INSTANTIATE_TEST_SUITE_P(Builtins, GBufferAgreement,
                         ::testing::Values("cornell", "spheres", "atrium"));

TEST(GBufferAgreementFiles, CornellObjAndWaterBottle) {
  TANDEM_ASSET(cornellSphereObj, "CornellBox/CornellBox-Sphere.obj");
  TANDEM_ASSET(waterBottle, "WaterBottle/glTF/WaterBottle.gltf");
  Scene c = loadScene(cornellSphereObj);
  CameraDesc cam;
  cam.position = {0, 0.795f, 3.4f};
  cam.lookAt = {0, 0.795f, 0};
  cam.vfovDeg = 39.3f;
  expectAgreement(compareGBuffers(c, cam, 256, 256), 256 * 256);
  Scene b = loadScene(waterBottle);
  cam.position = {0, 0.02f, 0.45f};
  cam.lookAt = {0, 0, 0};
  cam.vfovDeg = 45;
  cam.nearPlane = 0.005f;
  expectAgreement(compareGBuffers(b, cam, 200, 200), 200 * 200);
}

// A camera inside a room: walls, floor and ceiling all cross the near plane and pass behind
// the camera, exercising clipping.
TEST(GBufferAgreementFiles, CameraInsideGeometryNearPlaneClipping) {
  Scene s = makeCornellScene();
  CameraDesc cam;
  cam.position = {0.2f, 0.6f, -0.2f};
  cam.lookAt = {-1, 0.3f, -0.8f};
  cam.vfovDeg = 100;
  cam.nearPlane = 0.05f;
  expectAgreement(compareGBuffers(s, cam, 240, 160), 240 * 160);
}

TEST(GBufferAgreementFiles, OrthographicCamera) {
  Scene s = makeSpheresScene();
  CameraDesc cam = s.camera;
  cam.projection = Projection::Orthographic;
  cam.orthoHeight = 12;
  cam.nearPlane = 0.1f;
  cam.farPlane = 60;
  expectAgreement(compareGBuffers(s, cam, 240, 135), 240 * 135);
}

// Sub-pixel jitter moves raster sampling and primary rays identically.
TEST(GBufferAgreementFiles, JitteredCamera) {
  Scene s = makeSpheresScene();
  expectAgreement(compareGBuffers(s, s.camera, 240, 135, {0.37f, -0.21f}), 240 * 135);
  // And the jitter really moves the image: ids differ from the unjittered render somewhere.
  auto a = test::renderOnce(s, "deferred", 240, 135, s.camera);
  auto b = test::renderOnce(s, "deferred", 240, 135, s.camera, {0.37f, -0.21f});
  EXPECT_NE(a->context().input("depth").data, b->context().input("depth").data);
}

// When the camera moves, the raster G-buffer reprojects the motion of everything that stood
// still in vectors (raster/camera_motion.cpp) and computes it pixel by pixel only for objects
// that moved. Both must give exactly what motionVectorAtPixel gives every pixel, on every
// instruction set: `spheres` (animated spheres over a still floor), a camera that turns and
// moves between the frames, a width whose rows end in a partial vector.
TEST(GBufferMotion, CameraMotionMatchesThePerPixelReprojection) {
  const Scene scene = makeSpheresScene();
  CameraDesc a = scene.camera, b = scene.camera;
  b.position = b.position + Vec3(0.3f, 0.1f, -0.2f);
  b.lookAt = b.lookAt + Vec3(0.2f, 0.0f, 0.1f);
  const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  for (int64_t target : targets) {
    hwy::SetSupportedTargetsForTest(target);
    Renderer r(scene, Pipeline::load("deferred"), RenderSettings{.width = 197, .height = 111});
    r.renderFrameAt(0, 0.0f, a, a);
    r.renderFrameAt(1, 1.0f / 30.0f, b, b);
    const FrameContext& ctx = r.context();
    const View& v = ctx.views[0];
    ASSERT_TRUE(v.cameraMoved);
    const Buffer& pos = ctx.input("position");
    const Buffer& ids = ctx.input("object_id");
    const Buffer& motion = ctx.input("motion");
    size_t surfaces = 0, movedPixels = 0, mismatches = 0, stillMoving = 0;
    for (int y = 0; y < ctx.height; ++y)
      for (int x = 0; x < ctx.width; ++x) {
        const int id = int(ids.at(x, y)[0]);
        if (id < 0) continue;
        ++surfaces;
        movedPixels += ctx.frame.objects[size_t(id)].moved;
        const float* p = pos.at(x, y);
        const Vec2 want = motionVectorAtPixel(ctx.frame, v, id, Vec3(p[0], p[1], p[2]),
                                              Vec2{float(x) + 0.5f, float(y) + 0.5f});
        const float* got = motion.at(x, y);
        stillMoving += !ctx.frame.objects[size_t(id)].moved && std::abs(want.x) > 0.01f;
        if (std::memcmp(&want.x, &got[0], 4) != 0 || std::memcmp(&want.y, &got[1], 4) != 0)
          ++mismatches;
      }
    EXPECT_EQ(mismatches, 0u) << hwy::TargetName(target);
    EXPECT_GT(surfaces, size_t(ctx.width * ctx.height / 2));
    EXPECT_GT(movedPixels, 0u);        // some pixels belong to objects that moved
    EXPECT_LT(movedPixels, surfaces);  // and some to ones that stood still
  }
  hwy::SetSupportedTargetsForTest(0);
}
