// First users of the framework: TAA against a supersampled render of the same shading, and the
// accumulation baselines against the reference renderer's thin lens and motion blur.
#include <gtest/gtest.h>

#include <cmath>

#include "eval/metrics/metrics.h"
#include "eval/reference/supersample.h"
#include "pipeline/aov.h"
#include "scene/builtin_scenes.h"
#include "scene/primitives.h"
#include "test_util.h"

using namespace tandem;

namespace {

double meanAbsDiff(const Buffer& a, const Buffer& b) {
  double s = 0;
  for (size_t i = 0; i < a.data.size(); ++i) s += std::abs(double(a.data[i]) - b.data[i]);
  return s / double(a.data.size());
}

CameraDesc lensCamera() {
  CameraDesc c;
  c.position = {0, 0, 2};
  c.lookAt = {0, 0, 0};
  c.vfovDeg = 50;
  c.apertureDiameter = 0.25f;
  c.focusDistance = 4.0f;
  return c;
}

Buffer render(const Scene& s, const std::string& pipeline, const CameraDesc& cam,
              std::vector<std::string> sets, float shutter = 0.0f) {
  return test::renderHdr(s, pipeline, cam, sets, shutter);
}

}  // namespace

// TAA on a static shot converges to the supersampled image (64 spp: an 8 x 8 grid of sub-pixel
// offsets, the same deferred shading) far better than the aliased frame does, and holds still:
// its frame-to-frame change is a small fraction of what the jitter alone causes.
TEST(TAA, ConvergesToTheSupersampledImageAndStaysStill) {
  Scene s = makeAtriumScene();
  const RenderSettings rs{.width = 160, .height = 90};
  const Buffer truth = visualizeBuffer(supersample(s, "deferred", s.camera, rs, 8));
  Renderer taa(s, Pipeline::load("deferred-taa"), rs);
  Renderer jittered(s, Pipeline::load("deferred"), rs);
  Buffer lastTaa, lastJittered;
  double taaMotion = 0, rawMotion = 0;
  for (int i = 0; i < 24; ++i) {
    taa.renderFrame(0, s.camera);
    jittered.renderFrame(0, s.camera, taa.context().jitter);  // the same jitter, no TAA
    const Buffer a = visualizeBuffer(taa.context().input("taa"));
    const Buffer b = visualizeBuffer(jittered.context().input("hdr"));
    if (i >= 16) {  // converged: a full Halton cycle and more
      taaMotion += meanAbsDiff(a, lastTaa);
      rawMotion += meanAbsDiff(b, lastJittered);
    }
    lastTaa = a;
    lastJittered = b;
  }
  const Buffer aliased =
      visualizeBuffer(test::renderOnce(s, "deferred", 160, 90, s.camera)->context().input("hdr"));
  const double ssimTaa = ssim(lastTaa, truth), ssimAliased = ssim(aliased, truth);
  EXPECT_GT(ssimTaa, ssimAliased);
  EXPECT_GT(ssimTaa, 0.95);  // measured 0.969 (aliased 0.856) at 160 x 90
  EXPECT_LT(rmse(lastTaa, truth), rmse(aliased, truth));
  EXPECT_LT(taaMotion, 0.25 * rawMotion) << taaMotion << " vs " << rawMotion;
  // A cut drops the history: the next output is the current frame alone.
  taa.cut();
  taa.renderFrame(0, s.camera);
  EXPECT_EQ(taa.context().input("taa").data, taa.context().input("hdr").data);
}

// With many samples, accumulated depth of field approaches the reference renderer's thin lens
// (the same lens: aperture, focus distance), and accumulated motion blur its shutter.
TEST(Accumulation, ApproachesTheReferenceThinLensAndMotionBlur) {
  Scene s = test::emissiveSquares();
  const CameraDesc cam = lensCamera();
  const Buffer acc = render(s, "accumulation-dof", cam, {"accumulation.samples=256"});
  const Buffer ref =
      render(s, "reference", cam, {"pt_reference.spp=256", "pt_reference.progress=false"});
  CameraDesc pinhole = cam;
  pinhole.apertureDiameter = 0;
  const Buffer sharp = render(s, "deferred", pinhole, {});
  const double accSsim = ssim(visualizeBuffer(acc), visualizeBuffer(ref));
  const double sharpSsim = ssim(visualizeBuffer(sharp), visualizeBuffer(ref));
  // Measured 0.9997 (the pinhole image: 0.961); RMSE 0.0025 (pinhole 0.042).
  EXPECT_GT(accSsim, 0.995) << accSsim;
  EXPECT_LT(sharpSsim, accSsim);
  EXPECT_LT(rmse(acc, ref), 0.5 * rmse(sharp, ref));
  // Energy: the blur spreads the squares' light but keeps it (the mean agrees within 1 %).
  double ma = 0, mr = 0;
  for (size_t i = 0; i < acc.data.size(); ++i) ma += acc.data[i], mr += ref.data[i];
  EXPECT_NEAR(ma / mr, 1.0, 0.01);

  // Motion blur: the near square slides 1 m to the right while the shutter is open.
  Scene moving = test::emissiveSquares();
  Transform a, b;
  b.position.x = 1.0f;
  moving.objects[0].animation = {{0.0f, a}, {1.0f, b}};
  const Buffer accMb =
      render(moving, "accumulation-motion-blur", pinhole, {"accumulation.samples=256"}, 1.0f);
  const Buffer refMb = render(moving, "reference", pinhole,
                              {"pt_reference.spp=256", "pt_reference.progress=false"}, 1.0f);
  const Buffer still = render(moving, "deferred", pinhole, {}, 1.0f);
  const double mbSsim = ssim(visualizeBuffer(accMb), visualizeBuffer(refMb));
  // Measured 0.9994 (the still frame: 0.895); RMSE 0.0026 (still 0.139).
  EXPECT_GT(mbSsim, 0.995) << mbSsim;
  EXPECT_LT(rmse(accMb, refMb), 0.5 * rmse(still, refMb));
}

// Under camera motion TAA reprojects its history through the motion vectors: after a slow pan
// it is still closer to the supersampled image of the final view than the aliased frame is (a
// wrong reprojection would ghost and fall below it).
TEST(TAA, StaysAlignedWhileTheCameraMoves) {
  Scene s = makeAtriumScene();
  const RenderSettings rs{.width = 160, .height = 90};
  // A sideways pan (about a pixel per frame), then a turn.
  for (const Vec2 move : {Vec2{0.02f, 0.0f}, Vec2{0.0f, 0.3f}}) {
    Renderer taa(s, Pipeline::load("deferred-taa"), rs);
    CameraDesc cam = s.camera;
    for (int i = 0; i < 24; ++i) {
      cam.position.x += move.x;
      cam.lookAt.x += move.x;
      cam.lookAt.z += move.y;
      taa.renderFrame(i, cam);
    }
    const Buffer truth = visualizeBuffer(supersample(s, "deferred", cam, rs, 8));
    const Buffer aliased =
        visualizeBuffer(test::renderOnce(s, "deferred", 160, 90, cam)->context().input("hdr"));
    const Buffer out = visualizeBuffer(taa.context().input("taa"));
    // Before mip-mapped textures the single frame aliased and TAA won by 0.03 (pan 0.902 vs
    // 0.869, turn 0.937 vs 0.902). Trilinear filtering removed the texture aliasing, so in motion
    // TAA now trails the single frame slightly (pan 0.902 vs 0.929, turn 0.932 vs 0.950: its
    // resampled history blurs); history that failed to follow the camera would lose far more.
    EXPECT_GT(ssim(out, truth), ssim(aliased, truth) - 0.04) << move.x << " " << move.y;
    EXPECT_GT(ssim(out, truth), 0.88) << move.x << " " << move.y;
  }
}

// Texture level of detail (ray cones, trilinear mip-maps): against the supersampled truth (8 x 8
// samples, each filtering only its share of the pixel) the mip-mapped single frame is closer
// than the same frame sampling full-resolution texels (textureFootprint 0), which aliases on the
// atrium's distant floor tiles.
TEST(Textures, MipMapsApproachTheSupersampledImage) {
  Scene s = makeAtriumScene();
  RenderSettings rs{.width = 160, .height = 90};
  const Buffer truth = visualizeBuffer(supersample(s, "deferred", s.camera, rs, 8));
  Renderer mipmapped(s, Pipeline::load("deferred"), rs);
  mipmapped.renderFrame(0, s.camera);
  rs.textureFootprint = 0.0f;
  Renderer fullRes(s, Pipeline::load("deferred"), rs);
  fullRes.renderFrame(0, s.camera);
  const Buffer a = visualizeBuffer(mipmapped.context().input("hdr"));
  const Buffer b = visualizeBuffer(fullRes.context().input("hdr"));
  const double errMip = rmse(a, truth), errFull = rmse(b, truth);
  const double ssimMip = ssim(a, truth), ssimFull = ssim(b, truth);
  std::printf(
      "vs 8x8 supersampled: mip-mapped RMSE %.4f SSIM %.4f, full resolution RMSE %.4f "
      "SSIM %.4f\n",
      errMip, ssimMip, errFull, ssimFull);
  // Geometric edges alias alike in both (they dominate RMSE at this size); textures make the gap.
  EXPECT_LT(errMip, errFull);
  EXPECT_GT(ssimMip, ssimFull);
}
