// A model without lights or a camera: the default lighting rig lights it from the viewer's side,
// the automatic camera sees flat models face-on, and OBJ faces are drawn from both sides.
#include <gtest/gtest.h>

#include "scene/default_lights.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"
#include "test_util.h"

namespace tandem {
namespace {

// A 2 x 1 m quad in the plane x = 0.5 (normal +x or -x by winding), as an OBJ file.
Scene flatObj(const std::string& name, bool facingMinusX) {
  auto dir = test::scratchDir("default_view_" + name);
  test::writeText(dir / "flat.obj",
                  facingMinusX ? "v 0.5 0 0\nv 0.5 0 2\nv 0.5 1 2\nv 0.5 1 0\nf 1 2 3 4\n"
                               : "v 0.5 0 0\nv 0.5 1 0\nv 0.5 1 2\nv 0.5 0 2\nf 1 2 3 4\n");
  return loadScene((dir / "flat.obj").string());
}

double meanLuminance(const Buffer& hdr) {
  double sum = 0;
  for (size_t i = 0; i < hdr.pixelCount(); ++i)
    sum += luminance(hdr.rgb(int(i % hdr.width), int(i / hdr.width)));
  return sum / double(hdr.pixelCount());
}

TEST(AutoCamera, SeesAFlatModelFaceOnFromEitherSide) {
  for (bool minusX : {false, true}) {
    Scene s = flatObj(minusX ? "minus" : "plus", minusX);
    ASSERT_FALSE(s.hasCamera);
    const Vec3 d = autoViewDirection(s);
    EXPECT_GT(std::abs(d.x), 0.9f) << "the view looks along the plane's normal, not edge-on";
    CameraDesc c = defaultCamera(s);
    const Vec3 centre = s.bounds().center();
    EXPECT_NEAR(length(c.lookAt - centre), 0.0f, 1e-5f);
    // The bounding sphere fits the vertical field of view.
    const float radius = length(s.bounds().extent()) * 0.5f;
    EXPECT_GE(length(c.position - centre) * std::sin(radians(c.vfovDeg * 0.5f)), radius * 0.999f);
  }
}

// An 8 mm quad seen in stereo through the automatic camera: both eyes render it (a 64 mm pair
// would look past it on either side), and a model of human size keeps the human eye distance.
TEST(AutoCamera, StereoFramesASmallModelForBothEyes) {
  Scene s;
  Mesh quad = makePlane(1);
  for (Vec3& p : quad.positions) p = p * 0.004f;
  s.addObject("quad", s.addMesh(std::move(quad)), s.addMaterial(Material{}));
  s.lights.push_back(Light{});
  s.lights.back().type = LightType::Directional;
  s.lights.back().direction = {0, -1, 0};
  const CameraDesc c = defaultCamera(s);
  StereoDesc st;
  st.enabled = true;
  st = fitStereoToModel(s, c, st, false);
  EXPECT_LT(st.ipd, 0.001f);
  EXPECT_EQ(fitStereoToModel(s, c, StereoDesc{.enabled = true}, true).ipd, 0.064f);
  Renderer r(s, Pipeline::load("deferred"),
             RenderSettings{.width = 64, .height = 64, .stereo = st});
  r.renderFrame(0, c);
  const Buffer& hdr = r.output();
  for (int eye = 0; eye < 2; ++eye) {
    int covered = 0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) covered += luminance(hdr.rgb(eye * 64 + x, y)) > 0.05f;
    EXPECT_GT(covered, 64 * 64 / 20) << "eye " << eye;
  }
  Scene big;  // a 6 m ball, seen from 5 m away
  Mesh ball = makeUvSphere(16, 8);
  for (Vec3& p : ball.positions) p = p * 3.0f;
  big.addObject("ball", big.addMesh(std::move(ball)), big.addMaterial(Material{}));
  EXPECT_EQ(fitStereoToModel(big, defaultCamera(big), StereoDesc{.enabled = true}, false).ipd,
            0.064f);
}

TEST(AutoCamera, KeepsTheFrontViewForARoundModel) {
  // A sphere shows the same area from everywhere: the familiar front view stays.
  Scene s;
  s.addObject("ball", s.addMesh(makeUvSphere(32, 16)), s.addMaterial(Material{}));
  const Vec3 d = autoViewDirection(s);
  EXPECT_NEAR(d.x, 0.0f, 1e-5f);
  EXPECT_GT(d.z, 0.95f);
  EXPECT_GT(d.y, 0.05f);
}

TEST(DefaultLights, OnlyWhenNothingLightsTheScene) {
  Scene s = flatObj("rig", false);
  EXPECT_TRUE(needsDefaultLights(s));
  Scene lit = s;
  lit.lights.push_back(Light{});
  EXPECT_FALSE(needsDefaultLights(lit));
  // A bright emitter (a Cornell ceiling) is a lamp; a faint one is an accent.
  Scene lamp = s, glow = s;
  lamp.materials[0].emission = {5, 5, 5};
  glow.materials[0].emission = {0.2f, 0.2f, 0.2f};
  EXPECT_FALSE(needsDefaultLights(lamp));
  EXPECT_TRUE(needsDefaultLights(glow));
  EXPECT_FALSE(needsDefaultLights(loadScene("cornell")));
}

TEST(DefaultLights, RigLightsTheModelFromTheViewersSide) {
  for (bool minusX : {false, true}) {
    Scene s = flatObj(minusX ? "lit_minus" : "lit_plus", minusX);
    const CameraDesc cam = defaultCamera(s);
    const Buffer unlit = test::renderHdr(s, "deferred", cam, {});
    addDefaultLightRig(s, cam);
    EXPECT_TRUE(s.stats.defaultLightRig);
    ASSERT_EQ(s.lights.size(), 3u);
    EXPECT_TRUE(s.lights[0].castsShadows);
    // The key sun shines on the side the camera sees (light travels away from the viewer).
    EXPECT_GT(dot(s.lights[0].direction, normalize(cam.lookAt - cam.position)), 0.3f);
    const Buffer lit = test::renderHdr(s, "deferred", cam, {});
    // Unlit: only the 0.05 sky around a black quad. Lit: the quad (a large part of the frame)
    // is a well-exposed grey, far brighter than the sky.
    EXPECT_LT(meanLuminance(unlit), 0.06);
    EXPECT_GT(meanLuminance(lit), 0.15);
    for (float v : lit.data) ASSERT_TRUE(std::isfinite(v));
  }
}

TEST(ObjLoader, FacesAreDoubleSided) {
  // The quad facing away from the default +Z camera still renders (and is lit from the side it
  // is seen from: the shading normal flips towards the viewer).
  Scene s = flatObj("back", true);
  for (const Material& m : s.materials) EXPECT_TRUE(m.doubleSided);
  CameraDesc cam;
  cam.position = {3, 0.5f, 1};  // on the +x side: the quad's normal points to -x
  cam.lookAt = {0.5f, 0.5f, 1};
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = {-1, 0, 0};  // lights the +x side, the one the camera sees
  sun.intensity = 3;
  s.lights.push_back(sun);
  const Buffer img = test::renderHdr(s, "deferred", cam, {});
  const Vec3 centre = img.rgb(img.width / 2, img.height / 2);
  EXPECT_GT(luminance(centre), 0.3f) << "the back face is drawn and lit";
}

}  // namespace
}  // namespace tandem
