// Typed pass settings (ParamTable, nested shared settings), records (typed values passes hand
// each other, this frame or as history) and timings found through the pipeline (PassTimes).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <stdexcept>

#include "passes/baselines/rt_whitted.h"
#include "passes/heuristic/rt_secondary.h"
#include "pipeline/pass_times.h"
#include "pipeline/renderer.h"
#include "scene/builtin_scenes.h"
#include "test_util.h"

using namespace tandem;

namespace {

struct Inner {
  int depth = 3;
  float cutoff = 0.01f;
};

struct Outer {
  enum class Mode { A, B, C };
  float weight = 0.95f;
  bool on = true;
  Mode mode = Mode::B;
  Inner inner{.depth = 7};  // a nested default this pass changes
};

const ParamTable<Inner>& innerTable() {
  static const ParamTable<Inner> t =
      ParamTable<Inner>()
          .add(&Inner::depth, {.name = "depth", .min = 1, .max = 64, .doc = "d"})
          .add(&Inner::cutoff, {.name = "cutoff", .min = 0, .max = 1, .doc = "c"});
  return t;
}

class OuterPass : public SettingsPass<Outer> {
 public:
  std::string type() const override { return "outer"; }
  std::string description() const override { return "test"; }
  void execute(FrameContext&) override {}

 protected:
  const ParamTable<Outer>& tableFor() const override {
    static const ParamTable<Outer> t =
        ParamTable<Outer>()
            .add(&Outer::weight, {.name = "weight", .min = 0, .max = 1, .doc = "w"})
            .add(&Outer::on, {.name = "on", .doc = "o"})
            .add(&Outer::mode, {.name = "mode", .doc = "m", .choices = {"a", "b", "c"}})
            .nest(&Outer::inner, innerTable());
    return t;
  }
};

const ParamDesc& descOf(const Pass& p, const std::string& name) {
  static std::vector<ParamDesc> keep;
  keep = p.params();
  for (const ParamDesc& d : keep)
    if (d.name == name) return d;
  throw std::logic_error("no parameter " + name);
}

}  // namespace

// Types, defaults and ranges come from the members; a float's default reads as its shortest
// decimal; a nested struct's parameters take the outer initialiser's defaults.
TEST(TypedSettings, TableDescribesTheMembers) {
  OuterPass p;
  const std::vector<ParamDesc> d = p.params();
  ASSERT_EQ(d.size(), 5u);
  EXPECT_EQ(d[0].type, ParamType::Float);
  EXPECT_EQ(d[0].defaultValue, 0.95);  // not 0.949999988079071
  EXPECT_EQ(d[1].type, ParamType::Bool);
  EXPECT_EQ(d[1].defaultValue, 1.0);
  EXPECT_EQ(d[1].max, 1.0);
  EXPECT_EQ(d[2].type, ParamType::Enum);
  EXPECT_EQ(d[2].defaultValue, 1.0);
  EXPECT_EQ(d[2].max, 2.0);
  EXPECT_EQ(d[3].name, "depth");
  EXPECT_EQ(d[3].type, ParamType::Int);
  EXPECT_EQ(d[3].defaultValue, 7.0);  // Outer's initialiser, not Inner's 3
  EXPECT_EQ(d[4].defaultValue, 0.01);
  for (const ParamDesc& x : d) EXPECT_EQ(p.param(x.name), x.defaultValue) << x.name;
}

// A set value reaches the member (nested ones too), is range-checked first, and a reset
// restores the initialisers.
TEST(TypedSettings, SetAndResetReachTheStruct) {
  OuterPass p;
  p.setParam("weight", 0.5);
  p.setParam("mode", 2);
  p.setParam("depth", 12);
  p.setParam("cutoff", 0.25);
  EXPECT_EQ(p.settings().weight, 0.5f);
  EXPECT_EQ(p.settings().mode, Outer::Mode::C);
  EXPECT_EQ(p.settings().inner.depth, 12);
  EXPECT_EQ(p.settings().inner.cutoff, 0.25f);
  EXPECT_THROW(p.setParam("depth", 65), InputError);
  EXPECT_THROW(p.setParam("mode", 3), InputError);
  EXPECT_THROW(p.setParam("nope", 1), InputError);
  EXPECT_EQ(p.settings().inner.depth, 12);  // a rejected value changes nothing
  p.resetParams();
  EXPECT_EQ(p.settings().inner.depth, 7);
  EXPECT_EQ(p.settings().weight, 0.95f);
}

// The Whitted settings are one struct nested into every tracing pass: the all-rays baseline
// defaults to traced shadows, the hybrids to classified ones, and `--set` reaches the struct.
TEST(TypedSettings, WhittedSettingsAreSharedWithPerPassDefaults) {
  RTWhittedPass whitted;
  RTSecondaryPass secondary;
  EXPECT_EQ(descOf(whitted, "shadows").defaultValue, double(int(ShadowMode::Rays)));
  EXPECT_EQ(descOf(secondary, "shadows").defaultValue, double(int(ShadowMode::Classified)));
  EXPECT_EQ(whitted.settings().whitted.shadows, ShadowMode::Rays);
  Pipeline p = Pipeline::load("hybrid-all");
  p.setParam("rt_secondary.max_depth=3", "test");
  p.setParam("rt_secondary.shadows=maps", "test");
  int found = 0;
  for (const auto& pass : p.passes)
    if (auto* rt = dynamic_cast<RTSecondaryPass*>(pass.get())) {
      ++found;
      EXPECT_EQ(rt->settings().whitted.maxDepth, 3);
      EXPECT_EQ(rt->settings().whitted.settings().maxDepth, 3);
      EXPECT_EQ(rt->settings().whitted.shadows, ShadowMode::Maps);
    }
  EXPECT_EQ(found, 1);
}

namespace {

struct Tally {
  int frames = 0;
};

// Writes a record counting frames since the last reset: last frame's record + 1.
class TallyWriter : public Pass {
 public:
  std::string type() const override { return "tally_writer"; }
  std::string description() const override { return "test"; }
  std::vector<BufferSlot> inputs() const override {
    BufferSlot h = recordSlot("tally", "Tally");
    h.history = h.optional = true;
    return {h};
  }
  std::vector<BufferSlot> outputs() const override {
    return {recordSlot("tally", "Tally"), {"image", 1, BufferKind::Count}};
  }
  void execute(FrameContext& ctx) override {
    const Tally* last = ctx.previousRecord<Tally>(*this, "tally");
    ctx.outputRecord<Tally>(*this, "tally").frames = last ? last->frames + 1 : 1;
    ctx.output(*this, "image").fill(1.0f);
  }
};

// Reads this frame's record into an image (-1 without one).
class TallyReader : public Pass {
 public:
  std::string type() const override { return "tally_reader"; }
  std::string description() const override { return "test"; }
  std::vector<BufferSlot> inputs() const override {
    BufferSlot in = recordSlot("tally", recordType);
    in.optional = true;
    return {in, {"image", 1, BufferKind::Count}};
  }
  std::vector<BufferSlot> outputs() const override { return {{"out", 1, BufferKind::Count}}; }
  void execute(FrameContext& ctx) override {
    const Tally* t = ctx.inputRecord<Tally>(*this, "tally");
    ctx.output(*this, "out").fill(t ? float(t->frames) : -1.0f);
  }
  std::string recordType = "Tally";
};

Pipeline tallyPipeline() {
  Pipeline p;
  p.name = "tally";
  p.output = "out";
  p.passes.push_back(std::make_unique<TallyWriter>());
  p.passes.push_back(std::make_unique<TallyReader>());
  return p;
}

}  // namespace

// A record reaches its reader this frame and its writer the next (history); a reset, a disabled
// writer and a reader expecting another type are handled as for buffers.
TEST(Records, CarryTypedValuesThisFrameAndAsHistory) {
  const Scene s = makeCornellScene();
  Renderer r(s, tallyPipeline(), RenderSettings{.width = 8, .height = 4});
  for (int f = 0; f < 3; ++f) r.renderFrame(f, s.camera);
  EXPECT_EQ(r.context().input("out").data[0], 3.0f);
  // Records have no pixels: not listed among the buffers AOVs and the viewer can show.
  const std::vector<std::string> listed = r.pipeline().producedBuffers();
  EXPECT_EQ(std::count(listed.begin(), listed.end(), "tally"), 0);
  EXPECT_EQ(std::count(listed.begin(), listed.end(), "out"), 1);
  r.cut();
  r.renderFrame(3, s.camera);
  EXPECT_EQ(r.context().input("out").data[0], 1.0f);
  r.pipeline().passes[0]->enabled = false;  // bypassed: the record is empty, not stale
  r.renderFrame(4, s.camera);
  EXPECT_EQ(r.context().input("out").data[0], -1.0f);

  Pipeline wrong = tallyPipeline();
  static_cast<TallyReader&>(*wrong.passes[1]).recordType = "RtStats";
  try {
    wrong.validate("test");
    ADD_FAILURE() << "a record of another type was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("input 'tally' carries Tally, expected RtStats"),
              std::string::npos)
        << e.what();
  }
}

// Timings by pass type, whatever the pipeline's labels: hybrid-dof has two TAA passes (labelled
// taa_raster and taa_final), summed under "taa"; parts keep their part names; a type the pipeline
// lacks is an error rather than 0 ms.
TEST(PassTimesTest, FindsPassesByType) {
  const Pipeline p = Pipeline::load("hybrid-dof");
  FrameTimings ft;
  ft.passes = {{"scene_update", 0.5, 0},       {"taa_raster", 1, 0}, {"rt_dof", 4, 1000},
               {"rt_dof/shadow_maps", 1.5, 0}, {"taa_final", 2, 0},  {"history", 0.25, 0}};
  const PassTimes t(p, ft);
  EXPECT_EQ(t.ofType("taa"), 3.0);
  EXPECT_EQ(t.ofType("rt_dof"), 4.0);
  EXPECT_EQ(t.raysOf("rt_dof"), 1000.0);
  EXPECT_EQ(t.raysOf("taa"), 0.0);
  EXPECT_EQ(t.ofType("tonemap"), 0.0);  // in the pipeline, not timed here
  EXPECT_EQ(t.partOf("rt_dof", "shadow_maps"), 1.5);
  EXPECT_EQ(t.partOf("rt_dof", "nothing"), 0.0);
  EXPECT_THROW(t.ofType("foveated_pt"), std::logic_error);
  const std::map<std::string, double> byType = t.byType();
  EXPECT_EQ(byType.at("taa"), 3.0);
  EXPECT_EQ(byType.at("rt_dof/shadow_maps"), 1.5);
  EXPECT_EQ(byType.at("scene_update"), 0.5);
  EXPECT_EQ(byType.count("taa_final"), 0u);
}
