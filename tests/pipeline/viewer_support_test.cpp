// What the viewer builds on, tested without a window: generated parameter widgets, the fly
// camera, the profiler history, pass bypass, pipeline JSON round trips, camera JSON, and the
// reference pass converging over frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "pipeline/renderer.h"
#include "scene/camera_json.h"
#include "scene/loaders.h"
#include "viewer/fly_camera.h"
#include "viewer/frame_history.h"
#include "viewer/param_widgets.h"
#include "viewer/render_worker.h"

using namespace tandem;

// Every parameter of every built-in pass gets exactly one widget whose kind fits its type and
// whose range and default are the declared ones.
TEST(ViewerSupport, WidgetsForEveryParameterOfEveryPass) {
  size_t total = 0;
  for (const std::string& type : passTypes()) {
    auto pass = createPass(type);
    const std::vector<ParamDesc> params = pass->params();
    const std::vector<ParamWidget> widgets = paramWidgets(*pass);
    ASSERT_EQ(widgets.size(), params.size()) << type;
    for (size_t i = 0; i < params.size(); ++i) {
      const ParamDesc& d = params[i];
      const ParamWidget& w = widgets[i];
      EXPECT_EQ(w.param, d.name);
      EXPECT_FALSE(w.label.empty());
      EXPECT_NE(w.tooltip.find(d.doc), std::string::npos) << type << "." << d.name;
      EXPECT_EQ(w.min, d.min);
      EXPECT_EQ(w.max, d.max);
      EXPECT_EQ(w.defaultValue, d.defaultValue);
      EXPECT_GE(w.defaultValue, w.min);
      EXPECT_LE(w.defaultValue, w.max);
      switch (d.type) {
        case ParamType::Bool:
          EXPECT_EQ(w.kind, WidgetKind::Checkbox);
          break;
        case ParamType::Enum:
          EXPECT_EQ(w.kind, WidgetKind::Combo);
          EXPECT_EQ(w.choices, d.choices);
          break;
        case ParamType::Int:
          EXPECT_TRUE(w.kind == WidgetKind::SliderInt || w.kind == WidgetKind::DragInt);
          break;
        case ParamType::Float:
          EXPECT_TRUE(w.kind == WidgetKind::SliderFloat || w.kind == WidgetKind::SliderFloatLog ||
                      w.kind == WidgetKind::DragFloat);
          if (w.kind == WidgetKind::SliderFloatLog) {
            EXPECT_GT(w.min, 0.0);
          }
          break;
      }
      ++total;
    }
  }
  EXPECT_GE(total, 15u);  // the pass set has this many parameters at least
}

TEST(ViewerSupport, WidgetKindsFollowTheRange) {
  EXPECT_EQ(paramWidget({"a", ParamType::Float, 1, 0, 10, "", {}}).kind, WidgetKind::SliderFloat);
  EXPECT_EQ(paramWidget({"b", ParamType::Float, 1, 1e-3, 1e3, "", {}}).kind,
            WidgetKind::SliderFloatLog);
  EXPECT_EQ(paramWidget({"c", ParamType::Float, 0, 0, 1e9, "", {}}).kind, WidgetKind::DragFloat);
  EXPECT_EQ(paramWidget({"d", ParamType::Int, 4, 1, 64, "", {}}).kind, WidgetKind::SliderInt);
  EXPECT_EQ(paramWidget({"e", ParamType::Int, 4, 1, 1 << 20, "", {}}).kind, WidgetKind::DragInt);
}

TEST(ViewerSupport, FlyCameraRoundTripAndMotion) {
  CameraDesc d;
  d.position = {1, 2, 3};
  d.lookAt = {4, 1, -2};
  FlyCamera c = FlyCamera::fromDesc(d);
  CameraDesc back = c.toDesc(d);
  EXPECT_LT(length(back.position - d.position), 1e-5f);
  EXPECT_LT(length(normalize(back.lookAt - back.position) - normalize(d.lookAt - d.position)),
            1e-4f);
  // Forward moves along the view direction by speed x dt; up moves along world +Y.
  c.speed = 2;
  const Vec3 f = c.forward(), p0 = c.position;
  c.move(0, 0, 1, 0.5f);
  EXPECT_LT(length(c.position - (p0 + f)), 1e-5f);
  c.move(0, 1, 0, 1.0f);
  EXPECT_NEAR(c.position.y, p0.y + f.y + 2.0f, 1e-5f);
  // Right is horizontal and perpendicular to forward; pitch is clamped short of the pole.
  EXPECT_NEAR(dot(c.right(), c.forward()), 0.0f, 1e-5f);
  EXPECT_EQ(c.right().y, 0.0f);
  c.look(0, -100000);
  EXPECT_LE(c.pitchDeg, 89.0f);
}

TEST(ViewerSupport, FrameHistoryAveragesTheWindow) {
  FrameHistory h(3);
  for (int i = 1; i <= 5; ++i) h.add({{{"a", double(i), 0}, {"b", 10.0, 1000.0 * i}}, 10.0 + i});
  EXPECT_EQ(h.size(), 3u);
  auto rows = h.rows();
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].currentMs, 5.0);
  EXPECT_DOUBLE_EQ(rows[0].averageMs, 4.0);  // frames 3, 4, 5
  EXPECT_DOUBLE_EQ(rows[1].raysPerSecond, (3000.0 + 4000 + 5000) / 0.030);
  EXPECT_EQ(rows[0].raysPerSecond, 0.0);
  EXPECT_DOUBLE_EQ(h.averageFrameMs(), 14.0);
  EXPECT_NEAR(h.framesPerSecond(), 1000.0 / 14.0, 1e-9);
}

// A pipeline saved with its current parameters (as the viewer's panel does) loads back to the
// same parameters, enable flags included.
TEST(ViewerSupport, PipelineJsonRoundTrip) {
  for (const std::string& name : Pipeline::builtinNames()) {
    Pipeline p = Pipeline::load(name);
    p.passes.back()->enabled = false;
    Pipeline q = Pipeline::fromJson(p.toJson(), "round trip");
    ASSERT_EQ(q.passes.size(), p.passes.size());
    for (size_t i = 0; i < p.passes.size(); ++i) {
      EXPECT_EQ(q.passes[i]->enabled, p.passes[i]->enabled);
      for (const ParamDesc& d : p.passes[i]->params())
        EXPECT_EQ(q.passes[i]->param(d.name), p.passes[i]->param(d.name)) << name << " " << d.name;
    }
  }
  Pipeline h = Pipeline::load("hybrid-heuristic");
  h.setParam("heuristic.per_effect=true", "test");
  h.setParam("tonemap.operator=reinhard", "test");
  Pipeline h2 = Pipeline::fromJson(h.toJson(), "round trip");
  EXPECT_EQ(h2.toJson(), h.toJson());
}

// A disabled pass passes its input through: tonemap off shows the HDR image itself.
TEST(ViewerSupport, DisabledPassIsBypassed) {
  Scene s = loadScene("cornell");
  Pipeline p = Pipeline::load("deferred");
  p.passes.back()->enabled = false;  // tonemap
  Renderer r(s, std::move(p), RenderSettings{.width = 32, .height = 18});
  r.renderFrame(0, s.camera);
  EXPECT_EQ(r.output().data, r.context().input("hdr").data);
}

TEST(ViewerSupport, CameraJsonRoundTrip) {
  CameraDesc d;
  d.position = {1, 2, 3};
  d.lookAt = {0, 1, 0};
  d.vfovDeg = 50;
  d.apertureDiameter = 0.1f;
  d.apertureBlades = 5;
  CameraDesc e = cameraFromJson(cameraToJson(d), "test");
  EXPECT_EQ(e.position.x, 1.0f);
  EXPECT_EQ(e.lookAt.y, 1.0f);
  EXPECT_EQ(e.vfovDeg, 50.0f);
  EXPECT_EQ(e.apertureBlades, 5);
  std::vector<CameraKey> keys = {{0, {0, 1, 2}, {0, 0, 0}}, {2, {1, 1, 2}, {0, 0, 0}}};
  auto back = cameraPathFromJson(cameraPathToJson(keys), "test", d);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].time, 2.0f);
  EXPECT_EQ(back[1].position.x, 1.0f);
  EXPECT_THROW(cameraFromJson(Json{{"vfov", 500}}, "test"), InputError);
}

// Progressive mode: frames of 4 samples add up to exactly the one-shot 16-sample image, stop at
// the target, and start over when the camera moves.
TEST(ViewerSupport, ReferenceAccumulatesOverFramesAndResets) {
  Scene s = loadScene("cornell");
  Pipeline p = Pipeline::load("reference");
  p.setParam("pt_reference.accumulate=true", "test");
  p.setParam("pt_reference.frame_spp=4", "test");
  p.setParam("pt_reference.spp=16", "test");
  Renderer r(s, std::move(p), RenderSettings{.width = 40, .height = 24});
  for (int f = 0; f < 6; ++f) r.renderFrame(f, s.camera);  // the last two add nothing
  EXPECT_EQ(int(r.context().counters.at("spp")), 16);
  Pipeline one = Pipeline::load("reference");
  one.setParam("pt_reference.spp=16", "test");
  Renderer ref(s, std::move(one), RenderSettings{.width = 40, .height = 24});
  ref.renderFrame(0, s.camera);
  EXPECT_EQ(r.context().input("hdr").data, ref.context().input("hdr").data);
  CameraDesc moved = s.camera;
  moved.position.x += 0.1f;
  r.renderFrame(6, moved);
  EXPECT_EQ(int(r.context().counters.at("spp")), 4);
}

// The worker thread renders what the view asks; its output is the renderer's, parameter edits
// and pipeline switches take effect on a later frame, and bad edits are reported, not fatal.
TEST(ViewerSupport, RenderWorkerFramesEditsAndSwitches) {
  Scene s = loadScene("cornell");
  ViewState v;
  v.camera = s.camera;
  v.width = 48;
  v.height = 27;
  RenderWorker w(s, PipelineModel::load("deferred"), v);
  w.waitForFrames(2);
  FinishedFrame f;
  ASSERT_TRUE(w.takeFrame(f));
  ASSERT_EQ(f.width, 48);
  ASSERT_EQ(f.rgba.size(), size_t(48 * 27 * 4));
  Renderer ref(s, Pipeline::load("deferred"), RenderSettings{.width = 48, .height = 27});
  ref.renderFrame(0, s.camera);
  EXPECT_EQ(f.output.data, ref.output().data);
  EXPECT_FALSE(f.timings.passes.empty());
  // The window's pixels: the output rounded as std::lround, alpha opaque.
  for (size_t i = 0; i < f.output.pixelCount(); ++i) {
    for (size_t k = 0; k < 3; ++k)
      ASSERT_EQ(int(f.rgba[4 * i + k]),
                int(std::lround(std::clamp(f.output.data[3 * i + k], 0.0f, 1.0f) * 255.0f)))
          << "pixel " << i;
    ASSERT_EQ(f.rgba[4 * i + 3], 255);
  }
  // A buffer no pass reads (motion in deferred) is produced once it is shown.
  v.shownBuffer = "motion";
  w.setView(v);
  w.waitForFrames(w.framesFinished() + 3);
  ASSERT_TRUE(w.takeFrame(f));
  EXPECT_EQ(f.shown, "motion");
  v.shownBuffer.clear();
  w.setView(v);

  // tonemap.exposure = +2 stops brightens the image.
  const size_t tonemap = 1;  // deferred: vbuffer_shading, tonemap
  double before = 0, after = 0;
  for (float x : f.output.data) before += x;
  w.setParam(tonemap, "exposure", 2.0);
  w.waitForFrames(w.framesFinished() + 3);
  ASSERT_TRUE(w.takeFrame(f));
  for (float x : f.output.data) after += x;
  EXPECT_GT(after, before * 1.2);

  w.setParam(tonemap, "exposure", 1e9);  // out of range: reported, frames go on
  w.waitForFrames(w.framesFinished() + 3);
  EXPECT_NE(w.error().find("exposure"), std::string::npos);

  PipelineModel rt = PipelineModel::load("rt-only");
  w.setPipeline(rt);
  v.shownBuffer = "hdr";
  w.setView(v);
  w.waitForFrames(w.framesFinished() + 3);
  ASSERT_TRUE(w.takeFrame(f));
  EXPECT_EQ(f.shown, "hdr");
  EXPECT_EQ(f.timings.passes[1].name, "rt_whitted");
}
