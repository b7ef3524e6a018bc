// Declarations are the whole truth: a pass reads and writes only the slots it declares. Every
// built-in pipeline runs with each pass seeing only its declared buffers (what a second device
// holding only what was moved to it would see); reads of undeclared slots, reads by buffer name
// and writes of undeclared buffers are logic errors naming the pass and the slot.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <stdexcept>

#include "pipeline/renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/loaders.h"
#include "scene/scene_camera.h"

using namespace tandem;

namespace {

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

struct Shot {
  std::string scene;
  float shutter = 0;
  bool stereo = false;
};

// A scene that exercises the pipeline: the DoF shot for the depth-of-field pipelines, the moving
// ball with an open shutter for motion blur and interleaved sampling, stereo for foveation.
Shot shotFor(const std::string& pipeline) {
  const std::string scenes = std::string(TANDEM_SOURCE_DIR) + "/scenes/";
  if (endsWith(pipeline, "-dof")) return {scenes + "dof_fg.json"};
  if (pipeline.find("motion-blur") != std::string::npos || pipeline.rfind("interleaved", 0) == 0)
    return {scenes + "cornell_motion_blur.json", 0.5f};
  if (pipeline.rfind("foveated", 0) == 0) return {"cornell", 0, true};
  if (pipeline.rfind("hybrid", 0) == 0) return {scenes + "atrium_spheres.json"};
  return {"cornell"};
}

class DeclaredSlots : public ::testing::TestWithParam<std::string> {};

TEST_P(DeclaredSlots, EveryPassReadsAndWritesOnlyWhatItDeclares) {
  const std::string& name = GetParam();
  const Shot shot = shotFor(name);
  const Scene scene = loadScene(shot.scene);
  Pipeline pipeline = Pipeline::load(name);
  if (name == "reference") pipeline.setParam("pt_reference.spp=2", "test");
  Renderer r(
      scene, std::move(pipeline),
      RenderSettings{
          .width = 48, .height = 27, .shutter = shot.shutter, .stereo = {.enabled = shot.stereo}});
  r.context().isolatePasses = true;
  CameraDesc cam = defaultCamera(scene);
  // Three frames with a moving camera: history inputs are read from the second on.
  for (int f = 0; f < 3; ++f) {
    EXPECT_NO_THROW(r.renderFrame(f, cam)) << name << ", frame " << f;
    cam.position = cam.position + Vec3(0.01f, 0, 0);
    cam.lookAt = cam.lookAt + Vec3(0.01f, 0, 0);
  }
  EXPECT_EQ(r.output().width, shot.stereo ? 96 : 48);
  // Every counter the frames reported is declared by a pass of the pipeline (report() checks
  // the pass; this catches a write around it).
  for (const auto& [counter, value] : r.context().counters) {
    EXPECT_TRUE(r.pipeline().reportsCounter(counter)) << name << ": " << counter;
    EXPECT_TRUE(std::isfinite(value)) << name << ": " << counter;
  }
}

INSTANTIATE_TEST_SUITE_P(BuiltinPipelines, DeclaredSlots,
                         ::testing::ValuesIn(Pipeline::builtinNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string n = info.param;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

// A pass whose execute() does what a test asks of it.
class ProbePass : public Pass {
 public:
  enum class Does {
    ReadUndeclared,
    ReadHistoryAsInput,
    ReadByName,
    WriteUndeclared,
    ReportUndeclared,
    Nothing
  };
  explicit ProbePass(Does d) : does_(d) {}
  std::string type() const override { return "probe"; }
  std::string description() const override { return "test"; }
  std::vector<BufferSlot> inputs() const override {
    BufferSlot last{"last", 1};
    last.history = true;
    return {{"src", 1}, last};
  }
  std::vector<BufferSlot> outputs() const override { return {{"dst", 1}}; }
  std::vector<CounterDesc> counters() const override { return {{"probe/runs", "test"}}; }
  void execute(FrameContext& ctx) override {
    ctx.report(*this, "probe/runs", 1);
    switch (does_) {
      case Does::ReadUndeclared:
        ctx.optionalInput(*this, "scr");
        break;
      case Does::ReadHistoryAsInput:
        ctx.input(*this, "last");
        break;
      case Does::ReadByName:
        ctx.input("other");
        break;
      case Does::WriteUndeclared:
        ctx.buffers["stray"] = Buffer(1, 1, 1);
        break;
      case Does::ReportUndeclared:
        ctx.report(*this, "probe/rnus", 1);
        break;
      case Does::Nothing:
        break;
    }
    ctx.output(*this, "dst").fill(1.0f);
  }

 private:
  Does does_;
};

// Writes `src` and `other` (the probe's input, and a buffer the probe does not declare).
class SourcePass : public Pass {
 public:
  std::string type() const override { return "source"; }
  std::string description() const override { return "test"; }
  std::vector<BufferSlot> outputs() const override { return {{"src", 1}, {"other", 1}}; }
  void execute(FrameContext& ctx) override {
    ctx.output(*this, "src").fill(0.5f);
    ctx.output(*this, "other").fill(0.25f);
  }
};

std::string runProbe(ProbePass::Does does, bool isolate) {
  Pipeline p;
  p.name = "probe";
  p.output = "dst";
  p.passes.push_back(std::make_unique<SourcePass>());
  p.passes.push_back(std::make_unique<ProbePass>(does));
  p.passes.back()->bindings["last"] = "dst";
  const Scene scene = loadScene("cornell");
  Renderer r(scene, std::move(p), RenderSettings{.width = 8, .height = 8});
  r.context().isolatePasses = isolate;
  try {
    r.renderFrame(0, defaultCamera(scene));
  } catch (const std::logic_error& e) {
    return e.what();
  }
  return "";
}

TEST(DeclaredSlots, UndeclaredSlotsAreErrorsNamingPassAndSlot) {
  using D = ProbePass::Does;
  EXPECT_EQ(runProbe(D::Nothing, true), "");
  EXPECT_EQ(runProbe(D::ReadUndeclared, false),
            "pass 'probe' uses slot 'scr', which it does not declare as an input");
  EXPECT_EQ(runProbe(D::ReadHistoryAsInput, false),
            "pass 'probe' reads slot 'last' as this frame's value, but declares it as a history "
            "input");
  // By buffer name: outside checking mode the buffer is there; isolated, it is not.
  EXPECT_EQ(runProbe(D::ReadByName, false), "");
  EXPECT_EQ(runProbe(D::ReadByName, true), "no buffer 'other' in this frame");
  EXPECT_EQ(runProbe(D::WriteUndeclared, true),
            "pass 'probe' wrote buffer 'stray', which it does not declare");
  EXPECT_EQ(runProbe(D::ReportUndeclared, false),
            "pass 'probe' reports counter 'probe/rnus', which it does not declare");
}

// A reader asks for counters when it loads the pipeline: a name no pass declares is an input
// error naming the reader and the counter, before any frame.
TEST(DeclaredCounters, ReadersAskForDeclaredNamesWhenTheyLoad) {
  const Pipeline p = Pipeline::load("hybrid-heuristic");
  EXPECT_TRUE(p.reportsCounter("heuristic/selected"));
  EXPECT_TRUE(p.reportsCounter("rt_secondary/shadow_traced"));  // under the pass's label
  EXPECT_NO_THROW(p.requireCounter("heuristic/selected", "reader"));
  try {
    p.requireCounter("heuristic/selectd", "reader");
    ADD_FAILURE() << "a misspelt counter was accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("reader"), std::string::npos) << m;
    EXPECT_NE(m.find("heuristic/selectd"), std::string::npos) << m;
    EXPECT_NE(m.find("hybrid-heuristic"), std::string::npos) << m;
  }
  // A pipeline without the pass does not report its counters.
  EXPECT_FALSE(Pipeline::load("rt-only").reportsCounter("heuristic/selected"));
}

// Every multi-channel slot of every pass names each of its channels once (declared, or its
// kind's: rgb, xyz, dx dy), so readers index channels by name and `tandem pipeline` shows them.
TEST(DeclaredChannels, EveryMultiChannelSlotNamesItsChannels) {
  for (const std::string& type : passTypes()) {
    const std::unique_ptr<Pass> p = createPass(type);
    std::vector<BufferSlot> slots = p->inputs();
    for (const BufferSlot& s : p->outputs()) slots.push_back(s);
    for (const BufferSlot& s : slots) {
      if (s.kind == BufferKind::Record || s.channels == 1) continue;
      const std::vector<std::string> names = channelNamesOf(s);
      EXPECT_EQ(int(names.size()), s.channels) << type << "." << s.slot;
      EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size())
          << type << "." << s.slot << ": a channel named twice";
    }
  }
}

// A reader that expects other channels than the writer's is a load error naming both layouts.
TEST(DeclaredChannels, WriterAndReaderMustAgree) {
  Json j = Json::parse(Pipeline::builtinJson("hybrid-dof"));
  // Bind dof_composite's bokeh (intensity, foreground) to rt_hit (near_share, rays): same
  // channel count, kind and extent, different channels.
  for (Json& pass : j["passes"])
    if (pass["type"] == "dof_composite") pass["inputs"]["bokeh"] = "rt_hit";
  try {
    Pipeline::fromJson(j, "test.json");
    ADD_FAILURE() << "mismatched channels were accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("near_share, rays"), std::string::npos) << m;
    EXPECT_NE(m.find("intensity, foreground"), std::string::npos) << m;
  }
}

// Every registered pass declares each counter once, with a description.
TEST(DeclaredCounters, DeclarationsAreUniqueAndDescribed) {
  for (const std::string& type : passTypes()) {
    const std::unique_ptr<Pass> p = createPass(type);
    std::set<std::string> seen;
    for (const CounterDesc& c : p->counters()) {
      EXPECT_TRUE(seen.insert(c.name).second) << type << ": " << c.name << " twice";
      EXPECT_FALSE(c.doc.empty()) << type << ": " << c.name;
    }
  }
}

}  // namespace
