#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <fstream>
#include <set>

#include "core/error.h"
#include "passes/pass_docs.h"
#include "passes/pass_registry.h"
#include "pipeline/pipeline.h"
#include "pipeline/pipeline_graph.h"
#include "raster/gbuffer.h"
#include "scene/builtin_scenes.h"
#include "scene/loaders.h"
#include "test_util.h"

using namespace tandem;

namespace {
void expectPipelineError(const std::string& json, const std::string& fragment) {
  try {
    Pipeline::fromJson(Json::parse(json), "p.json");
    FAIL() << "accepted: " << json;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("p.json"), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(Pipeline, BuiltinsLoadAndValidate) {
  for (const std::string& name : Pipeline::builtinNames()) {
    Pipeline p = Pipeline::load(name);
    EXPECT_EQ(p.name, name);
    EXPECT_FALSE(p.passes.empty());
  }
}

TEST(Pipeline, WiringErrors) {
  expectPipelineError(R"({"passes": [{"type": "deferred_shading"}]})",
                      "is not produced by an earlier pass");
  expectPipelineError(R"({"passes": [{"type": "raster_gbuffer"}], "output": "hdr"})",
                      "'hdr' is not produced");
  expectPipelineError(
      R"({"passes": [{"type": "raster_gbuffer"}, {"type": "tonemap", "inputs": {"hdr": "depth"}}]})",
      "has 1 channels, expected 3");
}

TEST(Pipeline, DescriptionErrors) {
  expectPipelineError(R"({"passes": [{"type": "warp_drive"}]})", "unknown pass type 'warp_drive'");
  expectPipelineError(R"({"passes": [{"type": "tonemap", "params": {"exposur": 1}}]})",
                      "unknown parameter");
  expectPipelineError(R"({"passes": [{"type": "tonemap", "params": {"exposure": 99}}]})",
                      "out of range");
  expectPipelineError(R"({"passes": [{"type": "tonemap", "params": {"operator": "filmic"}}]})",
                      "unknown choice");
  expectPipelineError(R"({"passes": [{"type": "tonemap", "colour": 1}]})", "unknown field");
  expectPipelineError(R"({"passes": []})", "non-empty array");
}

TEST(Pipeline, ParametersRoundTripThroughJson) {
  Pipeline p =
      Pipeline::fromJson(Json::parse(R"({"name": "x", "passes": [{"type": "raster_gbuffer"},
      {"type": "deferred_shading"}, {"type": "tonemap", "params": {"exposure": 1.5, "operator": "reinhard"}}]})"),
                         "x");
  Pipeline q = Pipeline::fromJson(p.toJson(), "roundtrip");
  EXPECT_EQ(q.passes[2]->param("exposure"), 1.5);
  EXPECT_EQ(q.passes[2]->param("operator"), 1.0);
}

TEST(Pipeline, EveryPassTimedEveryFrame) {
  Scene s = makeCornellScene();
  auto r = std::make_unique<Renderer>(s, Pipeline::load("deferred"),
                                      RenderSettings{.width = 64, .height = 48});
  for (int f = 0; f < 3; ++f) {
    FrameTimings t = r->renderFrame(f, s.camera);
    ASSERT_EQ(t.passes.size(), 5u);  // scene_update + 2 passes + vbuffer_shading's 2 parts
    EXPECT_EQ(t.passes[1].name, "vbuffer_shading");
    EXPECT_EQ(t.passes[2].name, "vbuffer_shading/visibility");
    for (const PassTiming& p : t.passes) EXPECT_GE(p.ms, 0.0);
    EXPECT_GT(t.totalMs, 0.0);
  }
}

TEST(Pipeline, DeterministicImages) {
  Scene s = makeSpheresScene();
  auto a = test::renderOnce(s, "deferred", 160, 90, s.camera);
  auto b = test::renderOnce(s, "deferred", 160, 90, s.camera);
  EXPECT_EQ(a->output().data, b->output().data);
}

TEST(Pipeline, CornellDemoIsLitNotBlack) {
  Scene s = loadScene("cornell");  // as `tandem render` loads it: the ceiling quad becomes a light
  auto r = test::renderOnce(s, "deferred", 128, 128, s.camera);
  const Buffer& out = r->output();
  // The back wall's centre is lit by the ceiling light: clearly above black, below white.
  Vec3 back = out.rgb(64, 50);
  EXPECT_GT(luminance(back), 0.2f);
  EXPECT_LT(luminance(back), 0.95f);
  // The red wall is red.
  Vec3 left = out.rgb(8, 64);
  EXPECT_GT(left.x, 2 * left.y);
  for (float v : out.data) ASSERT_TRUE(std::isfinite(v));
}

TEST(Pipeline, MotionVectorsFollowAnimatedObject) {
  // The bobbing sphere of `spheres` moves 1.5 m up over 2 s: between two frames 1/30 s apart its
  // pixels move up on screen (negative y), while static geometry has zero motion.
  Scene s = makeSpheresScene();
  Renderer r(s, Pipeline::load("deferred"), RenderSettings{.width = 160, .height = 90});
  r.renderFrame(10, s.camera);
  r.renderFrame(11, s.camera);
  const Buffer& mv = r.context().input("motion");
  const Buffer& id = r.context().input("object_id");
  int animated = -1;
  for (size_t o = 0; o < s.objects.size(); ++o)
    if (s.objects[o].animated()) animated = int(o);
  ASSERT_GE(animated, 0);
  int moving = 0, still = 0;
  for (int y = 0; y < 90; ++y)
    for (int x = 0; x < 160; ++x) {
      int o = int(id.at(x, y)[0]);
      if (o == animated) {
        EXPECT_LT(mv.at(x, y)[1], -0.01f);
        ++moving;
      } else if (o >= 0) {
        EXPECT_NEAR(mv.at(x, y)[0], 0.0f, 1e-3f);
        ++still;
      }
    }
  EXPECT_GT(moving, 10);
  EXPECT_GT(still, 1000);
}

TEST(Pipeline, ImageIndependentOfThreadCount) {
  Scene s = makeAtriumScene();
  std::vector<float> one, all;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = test::renderOnce(s, "deferred", 200, 120, s.camera)->output().data;
  }
  all = test::renderOnce(s, "deferred", 200, 120, s.camera)->output().data;
  EXPECT_EQ(one, all);
}

// With a moving camera, a static point's motion is its pixel now minus its pixel in last frame's
// camera (checked against Camera::project); the sky moves only with camera rotation.
TEST(Pipeline, MotionVectorsFollowCamera) {
  Scene s = makeSpheresScene();
  CameraDesc a = s.camera, b = s.camera;
  b.position = a.position + Vec3(0.3f, 0.1f, 0);
  b.lookAt = a.lookAt + Vec3(0.5f, 0, 0);
  Renderer r(s, Pipeline::load("deferred"), RenderSettings{.width = 160, .height = 90});
  r.renderFrame(0, a);
  r.renderFrame(0, b);  // same scene time: only the camera moves
  const Buffer& mv = r.context().input("motion");
  const Buffer& pos = r.context().input("position");
  const Buffer& id = r.context().input("object_id");
  Camera now = Camera::make(b, 160, 90), before = Camera::make(a, 160, 90);
  int surface = 0, sky = 0;
  for (int y = 0; y < 90; y += 3)
    for (int x = 0; x < 160; x += 3) {
      Vec3 p = pos.rgb(x, y);
      Vec2 pn, pb;
      if (id.at(x, y)[0] < 0) {
        Vec3 o, d;
        now.generateRay(x + 0.5f, y + 0.5f, o, d);
        p = o + d * 1e6f;  // far away stands in for the point at infinity
        ++sky;
      } else {
        ++surface;
      }
      ASSERT_TRUE(now.project(p, pn) && before.project(p, pb));
      EXPECT_NEAR(mv.at(x, y)[0], pn.x - pb.x, 0.02f) << x << "," << y;
      EXPECT_NEAR(mv.at(x, y)[1], pn.y - pb.y, 0.02f) << x << "," << y;
    }
  EXPECT_GT(surface, 100);
  EXPECT_GT(sky, 5);
}

// docs/passes.md documents every pass type and every parameter (guards against drift).
// docs/passes.md is the generated reference, nothing else: every pass and parameter appears in
// it because it is printed from the passes themselves.
TEST(Pipeline, PassesDocIsGenerated) {
  std::ifstream in(std::string(TANDEM_SOURCE_DIR) + "/docs/passes.md");
  ASSERT_TRUE(in.good());
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string generated = passesMarkdown();
  for (const std::string& type : passTypes()) {
    EXPECT_NE(generated.find("### `" + type + "`"), std::string::npos) << type;
    for (const ParamDesc& p : createPass(type)->params())
      EXPECT_NE(generated.find("| `" + p.name + "` |"), std::string::npos) << type << "." << p.name;
  }
  EXPECT_TRUE(doc == generated)
      << "docs/passes.md is stale: run `tandem passes --out docs/passes.md`";
}

// The registry: one entry a type, each creating a pass of that type.
TEST(Pipeline, RegistryCreatesEveryType) {
  for (const PassEntry& e : passRegistry()) {
    ASSERT_NE(createPass(e.type), nullptr) << e.type;
    EXPECT_EQ(createPass(e.type)->type(), e.type);
    EXPECT_EQ(std::count(passTypes().begin(), passTypes().end(), e.type), 1) << e.type;
  }
  EXPECT_EQ(createPass("no_such_pass"), nullptr);
}

// Shading straight from the visibility buffer draws the deferred picture: the same radiance and,
// where they are read (here: all), the same G-buffer fields on every built-in scene (one resolve,
// one shading kernel).
TEST(Pipeline, VisibilityBufferShadingEqualsDeferred) {
  for (const std::string& name : builtinSceneNames()) {
    Scene s = makeBuiltinScene(name);
    auto gbuffer = test::renderOnce(s, "deferred-gbuffer", 160, 90, s.camera);
    auto vbuffer = test::renderOnce(s, "deferred", 160, 90, s.camera);
    std::vector<std::string> buffers = {"hdr"};
    for (const BufferSlot& g : gbufferSlots()) buffers.push_back(g.slot);
    for (const std::string& buffer : buffers) {
      const Buffer& a = gbuffer->context().input(buffer);
      const Buffer& b = vbuffer->context().input(buffer);
      ASSERT_TRUE(a.sameShape(b)) << name << " " << buffer;
      double worst = 0, range = 0;
      for (size_t i = 0; i < a.data.size(); ++i) {
        worst = std::max(worst, double(std::abs(a.data[i] - b.data[i])));
        range = std::max(range, double(std::abs(a.data[i])));
      }
      // Fields every scene fills (emission or motion may be zero throughout).
      if (buffer == "hdr" || buffer == "depth" || buffer == "position" || buffer == "normal") {
        EXPECT_GT(range, 0.0) << name << " " << buffer << " is empty";
      }
      EXPECT_LE(worst, 1e-6 * std::max(range, 1.0)) << name << " " << buffer;
    }
  }
}

// `tandem pipeline`: the passes in order with what each reads and writes, history marked, and a
// Graphviz graph with a box per pass and an edge per buffer written and read.
TEST(PipelineGraph, DescribesPassesBuffersAndHistory) {
  const Pipeline taa = Pipeline::load("deferred-taa");
  const std::string text = describePipeline(taa);
  EXPECT_NE(text.find("3. taa"), std::string::npos) << text;
  EXPECT_NE(text.find("reads  taa (3 colour: r, g, b; last frame's)"), std::string::npos) << text;
  // Channels by name: the G-buffer's diffuse target carries its opacity.
  EXPECT_NE(text.find("writes diffuse (4 material: r, g, b, opacity)"), std::string::npos) << text;
  EXPECT_NE(text.find("history (kept for the next frame): taa"), std::string::npos) << text;
  const std::string dot = pipelineDot(taa);
  EXPECT_EQ(dot.rfind("digraph \"deferred-taa\" {", 0), 0u);
  EXPECT_NE(dot.find("\"b:taa\" -> p2 [style=dashed"), std::string::npos) << dot;
  for (const std::string& name : Pipeline::builtinNames()) {
    const Pipeline p = Pipeline::load(name);
    const std::string g = pipelineDot(p);
    std::set<std::string> produced;
    size_t edges = 0;
    for (const auto& pass : p.passes)
      for (const BufferSlot& out : pass->outputs()) {
        produced.insert(pass->bufferName(out.slot));
        ++edges;
      }
    for (const auto& pass : p.passes)
      for (const BufferSlot& in : pass->inputs())
        edges += produced.count(pass->bufferName(in.slot));
    size_t arrows = 0, boxes = 0;
    for (size_t at = g.find(" -> "); at != std::string::npos; at = g.find(" -> ", at + 1)) ++arrows;
    for (size_t at = g.find("shape=box"); at != std::string::npos; at = g.find("shape=box", at + 1))
      ++boxes;
    EXPECT_EQ(arrows, edges) << name;
    EXPECT_EQ(boxes, p.passes.size()) << name;
  }
}
