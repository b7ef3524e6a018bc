// Interleaved sampling passes (Foster 2015): motion blur of a square moving at constant speed is
// its swept path with linear ramps (analytic); a defocused square spreads over its circle of
// confusion like the reference's thin lens, energy kept; N = 1 through a pinhole is the plain
// raster image; raster and ray-traced interleaving see the same samples; bad values are named.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <tbb/global_control.h>

#include "core/error.h"
#include "eval/metrics/metrics.h"
#include "pipeline/aov.h"
#include "scene/builtin_scenes.h"
#include "scene/loaders.h"
#include "scene/primitives.h"
#include "scene/thin_lens.h"
#include "test_util.h"

using namespace tandem;

namespace {

CameraDesc pinholeCamera() {
  CameraDesc c;
  c.position = {0, 0, 2};
  c.lookAt = {0, 0, 0};
  c.vfovDeg = 50;
  return c;
}

// One emissive 1 x 1 m square at z = -2 (4 m from the camera), over a black sky.
// Where the left and right edges of oneSquare's centre row (at rest) project, in pixels.
bool squareEdges(const CameraDesc& cd, int w, int h, Vec2& left, Vec2& right) {
  const Camera cam = Camera::make(cd, w, h);
  return cam.project({-0.5f, 0, -2}, left) && cam.project({0.5f, 0, -2}, right);
}

Scene oneSquare() {
  Scene s = test::emissiveSquares();
  s.objects.resize(1);
  s.objects[0].local.position = {0, 0, -2};
  return s;
}

// The share of the shutter a square of width S (pixels) whose left edge moves from L0 to L0 + D
// covers a point u of its row, clamp((u - L0) / D) - clamp((u - L0 - S) / D), averaged over
// pixel x (a pixel box filter).
double sweptCoverage(int x, double L0, double S, double D) {
  double c = 0;
  for (int q = 0; q < 64; ++q) {
    const double u = x + (q + 0.5) / 64.0;
    c += std::clamp((u - L0) / D, 0.0, 1.0) - std::clamp((u - L0 - S) / D, 0.0, 1.0);
  }
  return c / 64.0;
}

double sum(const Buffer& b) {
  double s = 0;
  for (float v : b.data) s += v;
  return s;
}

}  // namespace

// The square slides D = 1 m (as wide as itself) to the right while the shutter is open. A point
// of its centre row at screen x is covered for the fraction of the shutter
// clamp((x - L0) / D) - clamp((x - L0 - S) / D) (L0: left edge at open, S: width, D: travel, in
// pixels): zero outside the swept path, linear ramps inside. With a pixel box filter the pixel
// takes that fraction's average over its width.
TEST(Interleaved, MotionBlurOfAMovingSquareIsItsSweptPathWithLinearRamps) {
  Scene s = oneSquare();
  Transform a, b;  // on top of the square's placement
  b.position.x = 1.0f;
  s.objects[0].animation = {{0.0f, a}, {1.0f, b}};
  const int W = 96, H = 64;
  const CameraDesc cd = pinholeCamera();
  Vec2 left, right;
  ASSERT_TRUE(squareEdges(cd, W, H, left, right));
  const float L0 = left.x, S = right.x - left.x, D = S;
  const int row = int(left.y);
  for (const char* pipeline : {"interleaved-raster", "interleaved-rt"}) {
    const std::string pass =
        std::string(pipeline) == "interleaved-rt" ? "interleaved_rt" : "interleaved_raster";
    const Buffer img =
        test::renderHdr(s, pipeline, cd,
                        {pass + ".samples=64", pass + ".spp=16", pass + ".mode=motion_blur",
                         pass + ".filter=box", pass + ".filter_radius=0.5"},
                        1.0f, W, H);
    double err = 0, maxErr = 0;
    int inside = 0;
    // Least-squares slopes of the rising and falling ramps, measured and expected.
    double sx[2] = {}, sxx[2] = {}, sg[2] = {}, sxg[2] = {}, se[2] = {}, sxe[2] = {}, cnt[2] = {};
    for (int x = 0; x < W; ++x) {
      // The expected pixel value: the covered fraction averaged over the pixel.
      const double expect = sweptCoverage(x, L0, S, D);
      const double got = img.at(x, row)[0];  // emission red = 1
      if (expect == 0.0) {
        EXPECT_EQ(got, 0.0) << pipeline << " x " << x << " outside the swept path";
      }
      if (expect > 0) ++inside;
      err += (got - expect) * (got - expect);
      maxErr = std::max(maxErr, std::abs(got - expect));
      if (expect > 0.1 && expect < 0.9) {
        const int r = x + 0.5 < L0 + S ? 0 : 1;  // rising before the peak, falling after
        sx[r] += x, sxx[r] += double(x) * x, sg[r] += got, sxg[r] += x * got, se[r] += expect;
        sxe[r] += x * expect, cnt[r] += 1;
      }
    }
    // 16 samples a pixel: measured RMS below 0.035, worst 0.16 (2.5 samples of 16).
    EXPECT_LT(std::sqrt(err / W), 0.08) << pipeline;
    EXPECT_LT(maxErr, 0.25) << pipeline;
    for (int r = 0; r < 2; ++r) {
      ASSERT_GT(cnt[r], 8);
      const double den = cnt[r] * sxx[r] - sx[r] * sx[r];
      const double slopeGot = (cnt[r] * sxg[r] - sx[r] * sg[r]) / den;
      const double slopeExpect = (cnt[r] * sxe[r] - sx[r] * se[r]) / den;  // +-1 / D
      EXPECT_NEAR(slopeGot / slopeExpect, 1.0, 0.1) << pipeline << (r ? " falling" : " rising");
    }
    EXPECT_GT(inside, int(2 * S) - 2);
  }
}

// A defocused square spreads over its circle of confusion: the interleaved image agrees with the
// reference's thin lens (the same light transport: emission only), on a disk and on a hexagonal
// aperture, and the blur keeps the square's light.
TEST(Interleaved, DefocusAgreesWithTheReferenceThinLensAndKeepsEnergy) {
  const Scene s = test::emissiveSquares();
  for (int blades : {0, 6}) {
    CameraDesc cd = pinholeCamera();
    cd.apertureDiameter = 0.25f;
    cd.focusDistance = 4.0f;
    cd.apertureBlades = blades;
    const Buffer il = test::renderHdr(s, "interleaved-raster", cd,
                                      {"interleaved_raster.samples=64", "interleaved_raster.spp=16",
                                       "interleaved_raster.mode=dof"});
    const Buffer ref = test::renderHdr(s, "reference", cd,
                                       {"pt_reference.spp=256", "pt_reference.progress=false"});
    CameraDesc pin = cd;
    pin.apertureDiameter = 0;
    const Buffer sharp = test::renderHdr(s, "interleaved-raster", pin, {});
    const double q = ssim(visualizeBuffer(il), visualizeBuffer(ref));
    EXPECT_GT(q, 0.98) << "blades " << blades;
    EXPECT_LT(rmse(il, ref), 0.5 * rmse(sharp, ref)) << "blades " << blades;
    EXPECT_NEAR(sum(il) / sum(ref), 1.0, 0.02) << "blades " << blades;
  }
}

// A small square (30 cm, 5 px) far out of focus spreads to its circle of confusion: nothing lit
// beyond the CoC radius plus the square's half-size (and a pixel), the lit region centred on the
// square and reaching out to the CoC's edge, its light kept (the pinhole image's; 16 samples of
// the ~6 % of the disk the square covers per pixel: measured 0.7 % off).
TEST(Interleaved, ADefocusedPointSpreadsToItsCircleOfConfusion) {
  Scene s = oneSquare();
  s.objects[0].local.scale = {0.15f, 1, 0.15f};
  CameraDesc cd = pinholeCamera();
  cd.apertureDiameter = 0.8f;
  cd.focusDistance = 1.5f;  // the square at 4 m: far field, a CoC 23 px across
  const int W = 96, H = 64;
  const Camera cam = Camera::make(cd, W, H);
  Vec2 c, edge;
  ASSERT_TRUE(cam.project({0, 0, -2}, c));
  ASSERT_TRUE(cam.project({0.15f, 0, -2}, edge));
  const float half = edge.x - c.x, coc = 0.5f * ThinLens::of(cam).coc(4.0f);
  ASSERT_GT(coc, 10.0f);
  const std::vector<std::string> sets = {
      "interleaved_raster.samples=64", "interleaved_raster.spp=16", "interleaved_raster.mode=dof"};
  const Buffer blur = test::renderHdr(s, "interleaved-raster", cd, sets, 0.0f, W, H);
  CameraDesc pin = cd;
  pin.apertureDiameter = 0;
  const Buffer sharp = test::renderHdr(s, "interleaved-raster", pin, sets, 0.0f, W, H);
  double mx = 0, my = 0, mw = 0, reach = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const float v = blur.at(x, y)[0];
      const float dx = float(x) + 0.5f - c.x, dy = float(y) + 0.5f - c.y;
      const float d = std::hypot(dx, dy);
      if (d > coc + half * std::sqrt(2.0f) + 1.0f) {
        EXPECT_EQ(v, 0.0f) << x << "," << y << " beyond the CoC";
      }
      if (v > 0) reach = std::max(reach, double(d));
      mx += v * dx, my += v * dy, mw += v;
    }
  EXPECT_NEAR(mx / mw, 0.0, 1.0);
  EXPECT_NEAR(my / mw, 0.0, 1.0);
  EXPECT_GT(reach, 0.8 * coc);
  EXPECT_NEAR(sum(blur) / sum(sharp), 1.0, 0.05);
}

// N = 1 and aperture 0: one pair, one sample at each pixel centre, a pixel box: the plain raster
// G-buffer's image (deferred: the same rasterizer, texture filtering and shading).
TEST(Interleaved, OnePairThroughAPinholeIsThePlainRasterImage) {
  const Scene s = makeBuiltinScene("spheres");
  const CameraDesc cd = s.camera;
  const Buffer il =
      test::renderHdr(s, "interleaved-raster", cd,
                      {"interleaved_raster.samples=1", "interleaved_raster.spp=1",
                       "interleaved_raster.jitter=false", "interleaved_raster.filter=box",
                       "interleaved_raster.filter_radius=0.5", "interleaved_raster.shading=local"});
  const Buffer plain = test::renderHdr(s, "deferred", cd, {});
  EXPECT_LT(rmse(il, plain), 1e-4);
  EXPECT_GT(sum(il), 1.0);  // not black
}

// The image is the same whatever the thread count and schedule: samples are shaded and traced in
// fixed blocks, so the 8-wide batches (and their floating-point results) never depend on where the
// scheduler split the work. Whitted and local shading, raster and ray-traced visibility.
TEST(Interleaved, ImageDoesNotDependOnTheThreads) {
  // The motion-blur shot at 640 x 360, where the scheduler's splits used to change the batches.
  const Scene s = loadScene(std::string(TANDEM_SOURCE_DIR) + "/scenes/interleaved_motion.json");
  const std::vector<std::pair<std::string, std::vector<std::string>>> configs = {
      {"interleaved-raster", {}},
      {"interleaved-raster", {"interleaved_raster.shading=local"}},
      {"interleaved-rt", {}}};
  for (const auto& [pipeline, sets] : configs) {
    Buffer one;
    {
      tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
      one = test::renderHdr(s, pipeline, s.camera, sets, 0.1f, 640, 360);
    }
    const Buffer all = test::renderHdr(s, pipeline, s.camera, sets, 0.1f, 640, 360);
    const std::string what = pipeline + (sets.empty() ? "" : " " + sets[0]);
    EXPECT_TRUE(one.data == all.data) << what;
    EXPECT_GT(sum(all), 1.0) << what;
  }
}

// The raster and ray-traced variants find the same surfaces for the same samples (Embree motion
// blur and the thin-lens rays against the sheared projections), on a scene with both effects.
TEST(Interleaved, RasterAndRayTracedInterleavingAgree) {
  Scene s = makeBuiltinScene("spheres");
  Transform a, b;
  b.position.x = 0.3f;
  s.objects.back().animation = {{0.0f, a}, {1.0f, b}};  // a sphere
  CameraDesc cd = s.camera;
  cd.apertureDiameter = 0.1f;
  const std::vector<std::string> sets = {"interleaved_raster.samples=16",
                                         "interleaved_rt.samples=16"};
  const Buffer r = test::renderHdr(s, "interleaved-raster", cd, {sets[0]}, 1.0f);
  const Buffer t = test::renderHdr(s, "interleaved-rt", cd, {sets[1]}, 1.0f);
  EXPECT_GT(psnr(r, t), 40.0);
  EXPECT_GT(sum(r), 1.0);
}

TEST(Interleaved, BadValuesAreNamed) {
  const Scene s = test::emissiveSquares();
  try {
    test::renderHdr(s, "interleaved-raster", pinholeCamera(),
                    {"interleaved_raster.samples=6", "interleaved_raster.spp=4"});
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("interleaved_raster"), std::string::npos) << m;
    EXPECT_NE(m.find("samples"), std::string::npos) << m;
    EXPECT_NE(m.find("multiple"), std::string::npos) << m;
  }
  EXPECT_THROW(
      test::renderHdr(s, "interleaved-raster", pinholeCamera(), {"interleaved_raster.spp=0"}),
      InputError);
}

namespace {

// One frame of `pipeline` with the shutter open for 1 s, the renderer kept for its buffers.
std::unique_ptr<Renderer> renderMoving(const Scene& s, const std::string& pipeline,
                                       const CameraDesc& cd, int w = 96, int h = 64) {
  auto r = std::make_unique<Renderer>(s, Pipeline::load(pipeline),
                                      RenderSettings{.width = w, .height = h, .shutter = 1.0f});
  r->renderFrame(0, cd);
  return r;
}

Scene movingSquare() {
  Scene s = oneSquare();
  Transform a, b;
  b.position.x = 1.0f;
  s.objects[0].animation = {{0.0f, a}, {1.0f, b}};
  return s;
}

}  // namespace

// The velocity buffer carries each pixel's surface over the shutter: the square moves 1 m at
// 4 m, exactly its own projected width; the sky does not move.
TEST(MotionBlur, VelocityIsTheDisplacementOverTheShutter) {
  const CameraDesc cd = pinholeCamera();
  Vec2 left, right;
  ASSERT_TRUE(squareEdges(cd, 96, 64, left, right));
  auto r = renderMoving(movingSquare(), "postfx-motion-blur", cd);
  const Buffer& v = r->context().input("velocity");
  const int row = int(left.y);
  // The sharp image is at mid-shutter: the square then spans [left + D/2, right + D/2].
  const float D = right.x - left.x;
  int onSquare = 0;
  for (int x = 0; x < 96; ++x) {
    const float c = float(x) + 0.5f;
    if (c > left.x + 0.5f * D + 1 && c < right.x + 0.5f * D - 1) {
      EXPECT_NEAR(v.at(x, row)[0], D, 0.05f) << x;
      EXPECT_NEAR(v.at(x, row)[1], 0.0f, 0.05f) << x;
      ++onSquare;
    }
  }
  EXPECT_GT(onSquare, 10);
  EXPECT_EQ(v.at(2, 2)[0], 0.0f);  // sky
}

// McGuire et al.'s filter on the moving square: no light beyond the swept path, the blur spans
// the path (first and last lit pixels within 2 px of its ends), ramps in between. The filter is
// plausible rather than exact: inside the object's own mid-shutter footprint it cannot see the
// background it should let through, so the square stays too opaque there (measured: +24 % light,
// RMS 0.17 over the path against the analytic profile; interleaved sampling: below 0.035).
TEST(MotionBlur, PostProcessBlurFollowsTheSweptPath) {
  const CameraDesc cd = pinholeCamera();
  Vec2 left, right;
  ASSERT_TRUE(squareEdges(cd, 96, 64, left, right));
  const float L0 = left.x, S = right.x - left.x, D = S;
  const int row = int(left.y);
  auto r = renderMoving(movingSquare(), "postfx-motion-blur", cd);
  const Buffer& img = r->context().input("hdr");
  double got = 0, expected = 0, err = 0;
  int first = -1, last = -1;
  for (int x = 0; x < 96; ++x) {
    const double e = sweptCoverage(x, L0, S, D);
    const double g = img.at(x, row)[0];
    ASSERT_TRUE(std::isfinite(g));
    if (g > 0.01) {
      if (first < 0) first = x;
      last = x;
    }
    got += g;
    expected += e;
    err += (g - e) * (g - e);
  }
  EXPECT_NEAR(first, L0, 2.0);
  EXPECT_NEAR(last + 1, L0 + S + D, 2.0);
  EXPECT_GT(got / expected, 0.95);
  EXPECT_LT(got / expected, 1.3);
  EXPECT_LT(std::sqrt(err / (last - first + 1)), 0.2);
}

// Nothing moves: the mask is empty and the post-process returns the sharp image untouched.
// Something moves over a still background: the mask covers it and not the far corners; the
// hybrid is the interleaved image where the mask is 1 and the post-process where it is 0.
TEST(MotionBlur, MaskMarksMixedMotionAndTheCompositeFollowsIt) {
  const CameraDesc cd = pinholeCamera();
  {
    auto r = renderMoving(oneSquare(), "hybrid-motion-blur", cd);
    const Buffer& m = r->context().input("mb_mask");
    const Buffer& sharp = r->context().input("sharp");
    const Buffer& post = r->context().input("mb_postfx");
    double maskSum = 0;
    for (float v : m.data) maskSum += v;
    EXPECT_EQ(maskSum, 0.0);
    EXPECT_EQ(sharp.data, post.data);
  }
  // 192 x 128: the far corners lie more than a neighbourhood of 20-pixel tiles from the motion.
  auto r = renderMoving(movingSquare(), "hybrid-motion-blur", cd, 192, 128);
  const Buffer& m = r->context().input("mb_mask");
  const Buffer& post = r->context().input("mb_postfx");
  const Buffer& il = r->context().input("mb_interleaved");
  const Buffer& out = r->context().input("hdr");
  int ones = 0, zeros = 0;
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) {
      const float v = m.at(x, y)[0];
      if (v == 1.0f) {
        ++ones;
        for (int c = 0; c < 3; ++c) ASSERT_EQ(out.at(x, y)[c], il.at(x, y)[c]);
      } else if (v == 0.0f) {
        ++zeros;
        for (int c = 0; c < 3; ++c) ASSERT_EQ(out.at(x, y)[c], post.at(x, y)[c]);
      }
    }
  EXPECT_GT(ones, 100);
  EXPECT_GT(zeros, 100);
  EXPECT_EQ(m.at(0, 0)[0], 0.0f);
  EXPECT_EQ(m.at(191, 127)[0], 0.0f);
}

// The sharp image's frame-to-frame motion (for its temporal AA) is the displacement between the
// mid-shutter instants of consecutive frames: the square moves 1 m/s, the frames are 0.25 s
// apart, and the camera steps 0.1 m sideways between them (none while the shutter is open).
TEST(MotionBlur, SharpImageMotionIsTheDisplacementBetweenMidShutterInstants) {
  const int W = 96, H = 64;
  const CameraDesc cd0 = pinholeCamera();
  CameraDesc cd1 = cd0;
  cd1.position.x += 0.1f;
  cd1.lookAt.x += 0.1f;
  const Scene scene = movingSquare();  // the renderer keeps a reference
  Renderer r(scene, Pipeline::load("postfx-motion-blur"),
             RenderSettings{.width = W, .height = H, .shutter = 1.0f});
  r.renderFrameAt(0, 0.0f, cd0, cd0);
  r.renderFrameAt(1, 0.25f, cd1, cd1);
  const Buffer& m = r.context().input("sharp_motion");
  // The square's centre at mid-shutter: x = 0.5 m in frame 0, 0.75 m in frame 1. A plane facing
  // the camera moves as one in the image.
  Vec2 before, now, left, right;
  ASSERT_TRUE(Camera::make(cd0, W, H).project({0.5f, 0, -2}, before));
  ASSERT_TRUE(Camera::make(cd1, W, H).project({0.75f, 0, -2}, now));
  ASSERT_TRUE(Camera::make(cd1, W, H).project({0.25f, 0, -2}, left));
  ASSERT_TRUE(Camera::make(cd1, W, H).project({1.25f, 0, -2}, right));
  const int row = int(now.y);
  int onSquare = 0;
  for (int x = int(left.x) + 2; x < int(right.x) - 2; ++x) {
    EXPECT_NEAR(m.at(x, row)[0], now.x - before.x, 0.02f) << x;
    EXPECT_NEAR(m.at(x, row)[1], now.y - before.y, 0.02f) << x;
    ++onSquare;
  }
  EXPECT_GT(onSquare, 10);
  EXPECT_GT(std::abs(now.x - before.x), 1.0f);  // it does move
  // The sky only turns with the camera: a sideways step leaves it where it was.
  EXPECT_NEAR(m.at(2, 2)[0], 0.0f, 1e-3f);
}

// The post-process's sharp image is one jittered sample per pixel accumulated by temporal AA:
// on a still shot it approaches the 16-sample box-filtered image of the same shading, far
// closer than its aliased first frame; `converge` (equal weights for the first frames) gets
// there sooner than the plain exponential blend.
TEST(MotionBlur, TemporalSharpImageConvergesToTheSupersampledImage) {
  const Scene s = makeBuiltinScene("spheres");
  const int W = 160, H = 90;
  const Buffer truth = visualizeBuffer(test::renderHdr(
      s, "interleaved-raster", s.camera,
      {"interleaved_raster.samples=16", "interleaved_raster.spp=16",
       "interleaved_raster.mode=motion_blur", "interleaved_raster.shutter_time=0.5"},
      0.0f, W, H));
  auto run = [&](bool converge, int frames, Buffer* first) {
    Renderer r(s, Pipeline::load("postfx-motion-blur"), RenderSettings{.width = W, .height = H});
    r.pipeline().setParam(std::string("taa_sharp.converge=") + (converge ? "true" : "false"),
                          "test");
    for (int i = 0; i < frames; ++i) {
      r.renderFrame(i, s.camera);
      if (i == 0 && first) *first = visualizeBuffer(r.context().input("hdr"));
    }
    return visualizeBuffer(r.context().input("hdr"));
  };
  Buffer aliased;
  const Buffer converged = run(true, 16, &aliased);
  const double ssimAliased = ssim(aliased, truth), ssimTaa = ssim(converged, truth);
  // Measured: SSIM 0.969 against 0.871 for the first frame, RMSE 0.023 against 0.056; at frame
  // 4, RMSE 0.031 with `converge`, 0.040 without. Without the view's jitter every frame is the
  // first one and all three fail.
  EXPECT_GT(ssimTaa, ssimAliased + 0.02) << ssimTaa << " vs " << ssimAliased;
  EXPECT_LT(rmse(converged, truth), 0.7 * rmse(aliased, truth));
  EXPECT_LT(rmse(run(true, 4, nullptr), truth), rmse(run(false, 4, nullptr), truth));
}

// A camera sliding sideways over a floor: the blur varies smoothly with depth (parallax), which
// the post-process reconstructs; the `edges` mask leaves it to the post-process, while `spread`
// masks wherever the radii in a neighbourhood differ by more than a pixel. A square moving over
// a still background has motion edges, and both masks take it.
TEST(MotionBlur, EdgesMaskSkipsSmoothParallaxButTakesMotionBoundaries) {
  Scene floor;
  Material m;
  m.diffuse = {0.5f, 0.5f, 0.5f};
  const int mat = floor.addMaterial(m), mesh = floor.addMesh(makePlane(8));
  Transform xf;
  xf.position = {0, -1, -10};
  xf.scale = {30, 1, 30};
  floor.addObject("floor", mesh, mat, xf);
  floor.lights.push_back(Light{});
  CameraDesc open = pinholeCamera(), close = open;
  close.position.x += 0.3f;
  close.lookAt.x += 0.3f;
  auto maskedShare = [](const Scene& s, const CameraDesc& a, const CameraDesc& b,
                        const std::string& mask, int w, int h) {
    Renderer r(s, Pipeline::load("hybrid-motion-blur"),
               RenderSettings{.width = w, .height = h, .shutter = 1.0f});
    r.pipeline().setParam("postfx_motion_blur.mask=" + mask, "test");
    r.renderFrameAt(0, 0.0f, a, b);
    return r.context().counters.at("postfx_motion_blur/masked_tiles_percent");
  };
  // Measured: the floor 0 % (edges) against 71 % (spread) of the tiles; the square 36 % both.
  EXPECT_EQ(maskedShare(floor, open, close, "edges", 192, 128), 0.0);
  EXPECT_GT(maskedShare(floor, open, close, "spread", 192, 128), 10.0);
  const Scene square = movingSquare();
  const CameraDesc cd = pinholeCamera();
  EXPECT_GT(maskedShare(square, cd, cd, "edges", 192, 128), 5.0);
  EXPECT_GT(maskedShare(square, cd, cd, "spread", 192, 128), 5.0);
}
