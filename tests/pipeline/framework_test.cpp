// The pipeline framework's contract: buffer kinds and extents checked when a pipeline loads,
// history inputs kept across frames and dropped on every reset trigger, jitter requests, views
// (stereo), cameras through lens points and the rasterizer at shutter times.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "core/image_io.h"
#include "pipeline/aov.h"
#include "pipeline/renderer.h"
#include "raster/rasterizer.h"
#include "rt/primary_rays.h"
#include "scene/builtin_scenes.h"
#include "scene/primitives.h"
#include "test_util.h"
#include "viewer/render_worker.h"

using namespace tandem;

namespace {

// Writes `out` (1 channel) = last frame's value + 1, or 1 without history: the frame count since
// the last reset. `invalidating` is a parameter whose edit resets every history.
class CounterPass : public Pass {
 public:
  std::string type() const override { return "counter"; }
  std::string description() const override { return "test"; }
  std::vector<BufferSlot> inputs() const override {
    BufferSlot h{"count", 1, BufferKind::Count};
    h.history = true;
    return {h};
  }
  std::vector<BufferSlot> outputs() const override { return {{"count", 1, BufferKind::Count}}; }
  std::vector<ParamDesc> params() const override {
    return {{"invalidating", ParamType::Float, 0, 0, 1, "", {}, true},
            {"harmless", ParamType::Float, 0, 0, 1, "", {}}};
  }
  void resetHistory() override { ++resets; }
  void execute(FrameContext& ctx) override {
    const Buffer* prev = ctx.previous(*this, "count");
    Buffer& out = ctx.output(*this, "count");
    out.fill(prev ? prev->data[0] + 1.0f : 1.0f);
  }
  int resets = 0;
};

// A pass with configurable slots (wiring checks only; never executed).
class SlotPass : public Pass {
 public:
  SlotPass(std::vector<BufferSlot> in, std::vector<BufferSlot> out)
      : in_(std::move(in)), out_(std::move(out)) {}
  std::string type() const override { return "slots"; }
  std::string description() const override { return "test"; }
  std::vector<BufferSlot> inputs() const override { return in_; }
  std::vector<BufferSlot> outputs() const override { return out_; }
  void execute(FrameContext&) override {}

 private:
  std::vector<BufferSlot> in_, out_;
};

Pipeline pipelineOf(std::vector<std::unique_ptr<Pass>> passes, std::string output) {
  Pipeline p;
  p.name = "test";
  p.output = std::move(output);
  p.passes = std::move(passes);
  return p;
}

std::string validationError(Pipeline& p) {
  try {
    p.validate("test");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

CameraDesc frontCamera() {
  CameraDesc c;
  c.position = {0, 0, 2};
  c.lookAt = {0, 0, 0};
  c.vfovDeg = 60;
  return c;
}

}  // namespace

TEST(BufferContract, ValidateChecksKindExtentAndHistory) {
  using K = BufferKind;
  auto make = [](std::vector<BufferSlot> in, std::vector<BufferSlot> out) {
    return std::make_unique<SlotPass>(std::move(in), std::move(out));
  };
  {  // A half-extent buffer read as a frame-sized one.
    std::vector<std::unique_ptr<Pass>> v;
    v.push_back(make({}, {{"a", 3, K::Color, Extent::half()}}));
    v.push_back(make({{"a", 3}}, {{"b", 3}}));
    Pipeline p = pipelineOf(std::move(v), "b");
    EXPECT_NE(validationError(p).find("extent 1/2 frame, expected frame"), std::string::npos)
        << validationError(p);
  }
  {  // A depth buffer read as colour.
    std::vector<std::unique_ptr<Pass>> v;
    v.push_back(make({}, {{"a", 1, K::Depth}}));
    v.push_back(make({{"a", 1, K::Color}}, {{"b", 3}}));
    Pipeline p = pipelineOf(std::move(v), "b");
    EXPECT_NE(validationError(p).find("'a' is depth, expected colour"), std::string::npos)
        << validationError(p);
  }
  {  // History input that no pass produces; then produced by a later pass: fine.
    BufferSlot h{"late", 3};
    h.history = true;
    std::vector<std::unique_ptr<Pass>> v;
    v.push_back(make({h}, {{"b", 3}}));
    Pipeline p = pipelineOf(std::move(v), "b");
    EXPECT_NE(validationError(p).find("history input 'late' is not produced by any pass"),
              std::string::npos);
    p.passes.push_back(make({{"b", 3}}, {{"late", 3}}));
    EXPECT_EQ(validationError(p), "");
    EXPECT_EQ(p.historyBuffers(), std::vector<std::string>{"late"});
  }
  {  // An optional input may be missing; a fixed extent must match exactly.
    BufferSlot opt{"maybe", 1, K::Mask, Extent::fixed(1, 1)};
    opt.optional = true;
    std::vector<std::unique_ptr<Pass>> v;
    v.push_back(make({opt}, {{"b", 3}}));
    Pipeline p = pipelineOf(std::move(v), "b");
    EXPECT_EQ(validationError(p), "");
    p.passes.insert(p.passes.begin(), make({}, {{"maybe", 1, K::Mask, Extent::fixed(2, 1)}}));
    EXPECT_NE(validationError(p).find("extent 2x1, expected 1x1"), std::string::npos);
  }
}

// Every built-in pipeline is one of pipelines/*.json, byte for byte (one source).
TEST(BufferContract, BuiltinPipelinesAreTheJsonFiles) {
  std::vector<std::string> files;
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(TANDEM_SOURCE_DIR) + "/pipelines")) {
    files.push_back(e.path().stem().string());
    std::ifstream in(e.path());
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(Pipeline::builtinJson(files.back()), text) << files.back();
  }
  std::sort(files.begin(), files.end());
  EXPECT_EQ(Pipeline::builtinNames(), files);
}

// A 1/2-extent output keeps its size through the AOV writer (PNG and EXR) and the viewer.
TEST(BufferContract, ReducedExtentRoundTripsThroughAovAndViewer) {
  Scene s = makeCornellScene();
  const auto dir = test::scratchDir("reduced_extent");
  const std::string json = (dir / "half.json").string();
  test::writeText(json, R"({"name": "half", "passes": [
    {"type": "raster_gbuffer"}, {"type": "deferred_shading"}, {"type": "downsample"},
    {"type": "tonemap"}], "output": "output"})");
  Renderer r(s, Pipeline::load(json), RenderSettings{.width = 65, .height = 33});
  r.renderFrame(0, s.camera);
  const Buffer& half = r.context().input("half");
  EXPECT_EQ(half.width, 33);
  EXPECT_EQ(half.height, 17);
  EXPECT_EQ(r.context().input("quarter").width, 17);
  // The half image is the box-filtered frame.
  const Buffer& hdr = r.context().input("hdr");
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(
        half.at(10, 8)[c],
        0.25f * (hdr.at(20, 16)[c] + hdr.at(21, 16)[c] + hdr.at(20, 17)[c] + hdr.at(21, 17)[c]),
        1e-6f);
  writeBuffer((dir / "half.png").string(), half);
  writeBuffer((dir / "half.exr").string(), half);
  const Buffer png = loadImage((dir / "half.png").string());
  const Buffer exr = loadImage((dir / "half.exr").string());
  EXPECT_EQ(png.width, 33);
  EXPECT_EQ(png.height, 17);
  EXPECT_EQ(exr.data, half.data);
  // Shown as tonemapped colour (by kind), the same as the PNG.
  const Buffer shown = visualizeBuffer(half);
  EXPECT_NEAR(png.at(10, 8)[0], shown.at(10, 8)[0], 1.0f / 255.0f);

  ViewState view;
  view.camera = s.camera;
  view.width = 65;
  view.height = 33;
  view.shownBuffer = "half";
  RenderWorker worker(s, PipelineModel::load(json), view);
  worker.waitForFrames(1);
  FinishedFrame f;
  ASSERT_TRUE(worker.takeFrame(f));
  EXPECT_EQ(f.shown, "half");
  EXPECT_EQ(f.width, 33);
  EXPECT_EQ(f.height, 17);
  EXPECT_EQ(f.rgba.size(), size_t(33 * 17 * 4));
}

// History survives frames and is dropped by every reset trigger.
// shadow_map_fit: the maps' side follows the frame's larger side (the next power of two) where
// that is more than shadow_map_size, per view (a stereo frame's eyes, not the pair).
TEST(ShadowMapResolution, FitsTheLargerSideOfAView) {
  auto frameOf = [](std::vector<std::pair<int, int>> sizes) {
    FrameContext ctx;
    CameraDesc d;
    d.lookAt = {0, 0, -1};
    int x = 0;
    for (auto [w, h] : sizes) {
      View v;
      v.camera = Camera::make(d, w, h);
      v.x = x;
      x += w;
      ctx.views.push_back(v);
    }
    return ctx;
  };
  const FrameContext hd = frameOf({{1280, 720}}), small = frameOf({{96, 54}}),
                     stereo = frameOf({{600, 500}, {600, 500}}), exact = frameOf({{1024, 512}});
  EXPECT_EQ(hd.shadowMapResolution(1024, true), 2048);
  EXPECT_EQ(hd.shadowMapResolution(1024, false), 1024);
  EXPECT_EQ(hd.shadowMapResolution(4096, true), 4096);
  EXPECT_EQ(small.shadowMapResolution(1024, true), 1024);
  EXPECT_EQ(small.shadowMapResolution(64, true), 128);
  EXPECT_EQ(stereo.shadowMapResolution(256, true), 1024);  // an eye's 600 columns, not 1200
  EXPECT_EQ(exact.shadowMapResolution(512, true), 1024);
}

TEST(TemporalHooks, HistoryResetsOnEveryTrigger) {
  Scene s = makeCornellScene(), other = makeSpheresScene();
  auto counterPipeline = [] {
    std::vector<std::unique_ptr<Pass>> v;
    v.push_back(std::make_unique<CounterPass>());
    return pipelineOf(std::move(v), "count");
  };
  Renderer r(s, counterPipeline(), RenderSettings{.width = 8, .height = 4});
  auto count = [&] { return r.context().input("count").data[0]; };
  auto counter = [&] { return static_cast<CounterPass&>(*r.pipeline().passes[0]); };
  int frame = 0;
  auto next = [&](const CameraDesc& c) { r.renderFrame(frame++, c); };
  CameraDesc cam = s.camera;
  next(cam);
  EXPECT_EQ(count(), 1.0f);
  next(cam);
  next(cam);
  EXPECT_EQ(count(), 3.0f);
  cam.position = cam.position + Vec3(0.01f, 0, 0);  // a camera move is not a cut
  next(cam);
  EXPECT_EQ(count(), 4.0f);

  r.cut();
  next(cam);
  EXPECT_EQ(count(), 1.0f);
  EXPECT_EQ(r.lastResetReason(), "camera cut");
  next(cam);
  r.resize(10, 4);
  next(cam);
  EXPECT_EQ(count(), 1.0f);
  EXPECT_EQ(r.context().input("count").width, 10);
  next(cam);
  r.setScene(other);
  next(cam);
  EXPECT_EQ(count(), 1.0f);
  next(cam);
  r.pipeline().passes[0]->setParam("harmless", 0.5);  // not marked: history kept
  next(cam);
  EXPECT_EQ(count(), 3.0f);
  r.pipeline().passes[0]->setParam("invalidating", 0.5);
  next(cam);
  EXPECT_EQ(count(), 1.0f);
  next(cam);
  cam.apertureDiameter = 0.1f;  // a lens change is a new picture
  next(cam);
  EXPECT_EQ(count(), 1.0f);
  EXPECT_EQ(r.lastResetReason(), "lens change");
  next(cam);
  const int resetsBefore = counter().resets;
  r.setPipeline(counterPipeline());
  next(cam);
  EXPECT_EQ(count(), 1.0f);
  EXPECT_EQ(r.lastResetReason(), "pipeline switch");
  EXPECT_GE(resetsBefore, 6);  // the pass's own state was told each time
}

// A pass asking for jitter gets the Halton (2, 3) sequence, the same in every view and in the
// raster and ray-traced G-buffers; motion vectors never contain it.
TEST(TemporalHooks, JitterIsHaltonAndIdenticalInRasterAndRtGBuffers) {
  EXPECT_FLOAT_EQ(haltonJitter(1).x, 0.0f);  // 1/2 - 1/2
  EXPECT_FLOAT_EQ(haltonJitter(1).y, 1.0f / 3.0f - 0.5f);
  EXPECT_FLOAT_EQ(haltonJitter(2).x, 0.25f - 0.5f);
  EXPECT_FLOAT_EQ(haltonJitter(2).y, 2.0f / 3.0f - 0.5f);
  EXPECT_FLOAT_EQ(haltonJitter(3).x, 0.75f - 0.5f);
  EXPECT_FLOAT_EQ(haltonJitter(3).y, 1.0f / 9.0f - 0.5f);

  Scene s = makeCornellScene();
  Renderer taa(s, Pipeline::load("deferred-taa"), RenderSettings{.width = 64, .height = 36});
  for (int i = 0; i < 10; ++i) {
    taa.renderFrame(i, s.camera);
    const Vec2 j = haltonJitter(1 + i % 8);  // jitter_phases = 8
    EXPECT_EQ(taa.context().jitter.x, j.x);
    EXPECT_EQ(taa.context().jitter.y, j.y);
    // The view carries the jitter and its jittered camera; its own camera stays unjittered.
    const View& v = taa.context().views.front();
    EXPECT_EQ(v.jitter.x, j.x);
    EXPECT_EQ(v.jitteredCamera.jitter.x, j.x);
    EXPECT_EQ(v.jitteredCamera.jitter.y, j.y);
    EXPECT_EQ(v.camera.jitter.x, 0.0f);
    EXPECT_EQ(taa.context().camera().jitter.y, 0.0f);
  }
  // Without a request there is no jitter.
  auto plain = test::renderOnce(s, "deferred", 16, 9, s.camera);
  EXPECT_EQ(plain->context().jitter.x, 0.0f);

  // The same jitter in both G-buffers: ids and depths agree as for the unjittered frame.
  const Vec2 j = haltonJitter(5);
  auto raster = test::renderOnce(s, "deferred", 96, 54, s.camera, j);
  auto rt = test::renderOnce(s, "deferred-rt-gbuffer", 96, 54, s.camera, j);
  auto rasterPlain = test::renderOnce(s, "deferred", 96, 54, s.camera);
  const Buffer &ia = raster->context().input("object_id"), &ib = rt->context().input("object_id");
  int differ = 0, differFromPlain = 0;
  for (size_t i = 0; i < ia.data.size(); ++i) {
    differ += ia.data[i] != ib.data[i];
    differFromPlain += ia.data[i] != rasterPlain->context().input("object_id").data[i];
  }
  EXPECT_LE(differ, 3);            // edge pixels at most
  EXPECT_GT(differFromPlain, 10);  // the jitter did move the image
  const Buffer &da = raster->context().input("depth"), &db = rt->context().input("depth");
  for (size_t i = 0; i < da.data.size(); ++i) {
    if (ia.data[i] == ib.data[i] && ia.data[i] >= 0) {
      ASSERT_NEAR(da.data[i], db.data[i], 1e-4f);
    }
  }

  // A camera sliding along x past a wall facing it: the motion of every wall pixel is the same
  // constant, with or without jitter.
  Scene squares = test::emissiveSquares();
  CameraDesc a = frontCamera(), b = a;
  b.position.x += 0.02f;
  b.lookAt.x += 0.02f;
  for (Vec2 jj : {Vec2{0, 0}, haltonJitter(3)}) {
    Renderer m(squares, Pipeline::load("deferred"), RenderSettings{.width = 80, .height = 60});
    m.renderFrame(0, a, jj);
    m.renderFrame(1, b, jj);
    const Buffer& mv = m.context().input("motion");
    const Buffer& id = m.context().input("object_id");
    // The nearest square (object 0) at depth 4 from the camera: -0.02 * f_px / 4 pixels.
    const float fpx = 30.0f / std::tan(radians(30.0f));
    for (size_t i = 0; i < id.pixelCount(); ++i) {
      if (id.data[i] == 0) {
        ASSERT_NEAR(mv.data[2 * i], -0.02f * fpx / 4.0f, 1e-3f) << i;
      }
    }
  }
}

// Stereo eyes: a point at infinity lands on the same pixel with parallel axes; a near point shows
// the disparity ipd * f / z. Rendered side by side, each half is that eye's own mono render.
TEST(Views, StereoDisparityAndSideBySideImage) {
  CameraDesc c = frontCamera();
  StereoDesc st;
  st.enabled = true;
  st.ipd = 0.064f;
  const int w = 200, h = 100;
  const Camera left = Camera::make(eyeCamera(c, st, 0), w, h),
               right = Camera::make(eyeCamera(c, st, 1), w, h);
  const float fpx = 0.5f * float(h) / std::tan(radians(c.vfovDeg) * 0.5f);
  Vec2 pl, pr;
  const Vec3 far = c.position + normalize(Vec3(0.3f, 0.1f, -1.0f)) * 1e7f;
  ASSERT_TRUE(left.project(far, pl) && right.project(far, pr));
  EXPECT_NEAR(pl.x, pr.x, 1e-3f);
  EXPECT_NEAR(pl.y, pr.y, 1e-3f);
  const float z = 1.5f;
  const Vec3 near = c.position + Vec3(0.1f, 0.05f, -z);
  ASSERT_TRUE(left.project(near, pl) && right.project(near, pr));
  EXPECT_NEAR(pl.x - pr.x, st.ipd * fpx / z, 1e-3f);
  EXPECT_NEAR(pl.y, pr.y, 1e-4f);
  // Converged axes: a point at the convergence distance straight ahead has no disparity.
  st.converged = true;
  st.convergence = 3.0f;
  const Camera cl = Camera::make(eyeCamera(c, st, 0), w, h),
               cr = Camera::make(eyeCamera(c, st, 1), w, h);
  ASSERT_TRUE(cl.project(c.position + Vec3(0, 0, -3.0f), pl) &&
              cr.project(c.position + Vec3(0, 0, -3.0f), pr));
  EXPECT_NEAR(pl.x, pr.x, 1e-3f);

  st.converged = false;
  Scene s = makeCornellScene();
  for (const char* pipeline : {"deferred", "hybrid-heuristic", "deferred-rt-gbuffer"}) {
    RenderSettings rs{.width = 48, .height = 32};
    rs.stereo = st;
    Renderer stereo(s, Pipeline::load(pipeline), rs);
    stereo.renderFrame(0, s.camera);
    const Buffer& out = stereo.output();
    ASSERT_EQ(out.width, 96);
    ASSERT_EQ(out.height, 32);
    for (int e = 0; e < 2; ++e) {
      auto mono = test::renderOnce(s, pipeline, 48, 32, eyeCamera(s.camera, st, e));
      const Buffer& m = mono->output();
      for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 48; ++x) {
          for (int k = 0; k < 3; ++k) {
            ASSERT_EQ(out.at(x + 48 * e, y)[k], m.at(x, y)[k]) << pipeline << " eye " << e;
          }
        }
      }
    }
  }
}

// Through a lens point, the sheared camera's ray of a pixel is the thin-lens ray of that pixel
// and lens point; focus-plane points do not move, others move by the lens offset's parallax.
TEST(TimeAndLens, LensPointCameraMatchesThinLensRays) {
  CameraDesc d = frontCamera();
  d.apertureDiameter = 0.2f;
  d.focusDistance = 4.0f;
  const Camera centre = Camera::make(d, 120, 80);
  for (float u1 : {0.1f, 0.5f, 0.85f})
    for (float u2 : {0.2f, 0.7f}) {
      const Vec2 l = centre.lensPoint(u1, u2);
      const Camera lensCam = Camera::make(d, 120, 80, {0, 0}, l);
      for (Vec2 px : {Vec2{10.5f, 20.5f}, Vec2{60, 40}, Vec2{119.5f, 0.5f}}) {
        Vec3 o1, d1, o2, d2;
        centre.generateThinLensRay(px.x, px.y, u1, u2, o1, d1);
        lensCam.generateRay(px.x, px.y, o2, d2);
        EXPECT_NEAR(length(o1 - o2), 0.0f, 1e-5f);
        EXPECT_NEAR(length(d1 - d2), 0.0f, 1e-5f);
        // The lens camera's projection maps points of that ray back to the pixel.
        Vec2 back;
        ASSERT_TRUE(lensCam.project(o2 + d2 * 7.0f, back));
        EXPECT_NEAR(back.x, px.x, 2e-3f);
        EXPECT_NEAR(back.y, px.y, 2e-3f);
      }
      // A point of the focus plane projects where it does through the lens centre.
      Vec2 a, b;
      const Vec3 onFocus = d.position + Vec3(0.5f, -0.3f, -4.0f);
      ASSERT_TRUE(centre.project(onFocus, a) && lensCam.project(onFocus, b));
      EXPECT_NEAR(a.x, b.x, 1e-3f);
      EXPECT_NEAR(a.y, b.y, 1e-3f);
    }
}

// The rasterizer draws moving objects where positionAt puts them at shutter fraction tau, and
// through a lens point a square off the focus plane shifts by the expected parallax.
TEST(TimeAndLens, RasterizerAtShutterTimeAndLensPoint) {
  Scene s = test::emissiveSquares();
  Transform a, b;  // animation applies on top of the object's own transform
  b.position.x = 1.0f;
  s.objects[0].animation = {{0.0f, a}, {1.0f, b}};
  FrameScene fs;
  fs.update(s, 0.0f, -1.0f / 30.0f, 1.0f);  // shutter open for 1 s
  ASSERT_FALSE(fs.objects[0].stepPositions.empty());
  const Camera cam = Camera::make(frontCamera(), 160, 120);
  Rasterizer raster;
  for (float tau : {0.0f, 0.3f, 0.75f}) {
    VisibilityBuffer vis;
    raster.render(fs, cam, vis, nullptr, tau);
    // Project the square's corners at tau: every pixel centre well inside is drawn by object 0.
    Vec2 lo(1e9f, 1e9f), hi(-1e9f, -1e9f);
    for (size_t v = 0; v < fs.objects[0].positions.size(); ++v) {
      Vec2 p;
      ASSERT_TRUE(cam.project(positionAt(fs.objects[0], v, tau), p));
      lo = Vec2(std::min(lo.x, p.x), std::min(lo.y, p.y));
      hi = Vec2(std::max(hi.x, p.x), std::max(hi.y, p.y));
    }
    int inside = 0, wrong = 0;
    for (int y = 0; y < 120; ++y)
      for (int x = 0; x < 160; ++x) {
        const float cx = float(x) + 0.5f, cy = float(y) + 0.5f;
        const bool in = cx > lo.x + 1 && cx < hi.x - 1 && cy > lo.y + 1 && cy < hi.y - 1;
        const bool out = cx < lo.x - 1 || cx > hi.x + 1 || cy < lo.y - 1 || cy > hi.y + 1;
        const bool drawn = vis.object[size_t(y) * 160 + size_t(x)] == 0;
        inside += in;
        wrong += (in && !drawn) || (out && drawn);
      }
    EXPECT_GT(inside, 50) << tau;
    EXPECT_EQ(wrong, 0) << tau;
    // Primary rays at the same tau see the same square (Embree's motion blur at the ray time).
    RayTracer rt;
    rt.update(fs);
    std::atomic<int> disagree{0};  // the body runs on worker threads
    tracePrimaryRays(
        cam, rt,
        [&](int x, int y, const Ray&, const Hit& h) {
          const bool rayHit = h.object == 0,
                     rasterHit = vis.object[size_t(y) * 160 + size_t(x)] == 0;
          if (rayHit != rasterHit) ++disagree;  // edge pixels only
        },
        tau);
    EXPECT_LE(disagree.load(), 8) << tau;
  }
  // Lens point 40 cm to the right, focus at 4 m: the square at 4 m (object 0) stays, the one at
  // 6 m (object 1, unoccluded) moves by l f_px (1/focus - 1/z) pixels (the sheared projection).
  CameraDesc d = frontCamera();
  d.apertureDiameter = 0.2f;
  d.focusDistance = 4.0f;
  const Scene stillScene = test::emissiveSquares();
  FrameScene still;
  still.update(stillScene, 0.0f, 0.0f);
  const Camera c0 = Camera::make(d, 160, 120), c1 = Camera::make(d, 160, 120, {0, 0}, {0.4f, 0});
  VisibilityBuffer v0, v1;
  raster.render(still, c0, v0);
  raster.render(still, c1, v1);
  auto centroidX = [](const VisibilityBuffer& v, uint32_t obj) {
    double sx = 0, n = 0;
    for (int y = 0; y < v.height; ++y)
      for (int x = 0; x < v.width; ++x)
        if (v.object[size_t(y) * size_t(v.width) + size_t(x)] == obj) sx += x + 0.5, n += 1;
    return sx / n;
  };
  const float fpx = 60.0f / std::tan(radians(30.0f));
  EXPECT_NEAR(centroidX(v1, 0) - centroidX(v0, 0), 0.0, 0.05);
  EXPECT_NEAR(centroidX(v1, 1) - centroidX(v0, 1), 0.4 * fpx * (1.0 / 4.0 - 1.0 / 6.0), 0.5);
}

// Outputs no pass, history or caller reads are skipped when the caller allows it (bench, render,
// the viewer), with the same image; what the caller lists in `wanted` is produced and equals the
// full frame's buffer.
TEST(Outputs, UnreadOutputsAreSkippedWithTheSameImage) {
  const Scene s = makeAtriumScene();
  CameraDesc a = s.camera, b = s.camera;
  b.position = b.position + Vec3(0.05f, 0.0f, 0.02f);  // a moving camera: motion is non-zero
  auto run = [&](const std::string& pipeline, bool keepAll, std::set<std::string> wanted) {
    auto r = std::make_unique<Renderer>(s, Pipeline::load(pipeline),
                                        RenderSettings{.width = 64, .height = 48});
    r->context().keepAllOutputs = keepAll;
    r->context().wanted = std::move(wanted);
    r->renderFrame(0, a);
    r->renderFrame(1, b);
    return r;
  };
  for (const char* p : {"deferred", "deferred-rt-gbuffer", "deferred-gbuffer"}) {
    SCOPED_TRACE(p);
    auto full = run(p, true, {});
    auto lean = run(p, false, {});
    const FrameContext& f = full->context();
    const FrameContext& l = lean->context();
    ASSERT_TRUE(f.has("depth"));
    EXPECT_FALSE(l.has("depth"));  // nothing in these pipelines reads depth or motion
    EXPECT_FALSE(l.has("motion"));
    EXPECT_EQ(l.input("hdr").data, f.input("hdr").data);
    EXPECT_EQ(lean->output().data, full->output().data);
    auto asked = run(p, false, {"depth"});
    EXPECT_EQ(asked->context().input("depth").data, f.input("depth").data);
  }
  // `deferred` shades from the visibility buffer: its G-buffer is written only when asked for,
  // and then equals the full frame's.
  auto lean = run("deferred", false, {});
  auto normalAsked = run("deferred", false, {"normal"});
  auto fullDeferred = run("deferred", true, {});
  EXPECT_FALSE(lean->context().has("normal"));
  EXPECT_FALSE(lean->context().has("position"));
  EXPECT_EQ(normalAsked->context().input("normal").data,
            fullDeferred->context().input("normal").data);
  EXPECT_EQ(normalAsked->output().data, lean->output().data);
  // Motion is read by TAA, so it is produced; here and when asked for, it is the full frame's.
  auto full = run("deferred", true, {});
  auto motionAsked = run("deferred", false, {"motion"});
  const Buffer& m = full->context().input("motion");
  EXPECT_EQ(motionAsked->context().input("motion").data, m.data);
  EXPECT_TRUE(std::any_of(m.data.begin(), m.data.end(), [](float v) { return v != 0.0f; }));
  auto taa = run("deferred-taa", false, {});
  const Buffer& tm = taa->context().input("motion");  // jittered: other surface points
  EXPECT_TRUE(std::any_of(tm.data.begin(), tm.data.end(), [](float v) { return v != 0.0f; }));
  EXPECT_FALSE(taa->context().has("depth"));
}
