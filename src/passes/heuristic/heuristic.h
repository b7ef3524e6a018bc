// heuristic: Walewski et al. 2019 §3.2. Every frame, for every object: visible area A (pixel count
// from the object-id buffer, one pass over the image), P (projected bounding-box centre, [0.01,
// 1]), D (distance to the camera), V = A P / D (eq. 1), Q (lights; + lights + 1 if reflective;
// + lights + 4 if refractive), S (selected last frame), C = A Q E (eq. 2), R = (S I + V) K (eq. 3).
// Then phase 3: nodes sorted by cost, each pointing to cheaper-or-equal, more relevant nodes,
// walked while budget T remains. Output: the per-pixel heuristic mask (Figure 2h), one channel
// per effect (shadow, reflection, refraction; the paper's mode sets all three together).
// Beyond the paper, each switchable (defaults keep the paper's behaviour):
//  - budget_ms: costs become predicted CPU ms (A E x the CPU ms per pixel the RT pass measured
//    for that object and effect, recursion included) and T is the budget times the measured
//    ratio of predicted CPU ms to RT wall ms (smoothed), so the RT stage follows the budget;
//  - per_effect: nodes are (object, effect) pairs, so an object may get shadows but not its
//    reflection (the paper's future work);
//  - partial_objects (ms budget; off: it measured worse tracking): the unspent budget buys the
//    central part of the most relevant node left out (mask set on that share of its pixels
//    nearest the view centre);
//  - count_recursion: Q is the rays per pixel the RT pass actually traced for the object and
//    effect (recursion included), the paper's Q being the prior until it has been traced;
//  - deadline (ms budget): the budget becomes rt_secondary's deadline. The walk selects
//    `overcommit` times the budget, rt_secondary traces the selection most relevant first and
//    stops at the deadline (what it reached is its traced_mask), so a misprediction costs the
//    least relevant pixels instead of time. The calibration then learns from the cost of what was
//    traced.
// Inputs: object_id, rt_stats (last frame's, a history input). Outputs: heuristic_mask (3
// channels), rt_request (a record: whether rt_secondary times each object and effect, and its
// deadline), heuristic_order (objects x 1: per effect, the node's rank by relevancy among the
// selected, 0 first; -1 not selected).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/buffer.h"
#include "passes/heuristic/rt_feedback.h"
#include "pipeline/param_table.h"
#include "scene/camera.h"
#include "scene/frame_scene.h"

namespace tandem {

struct ObjectHeuristic {
  int object = -1;
  double A = 0, P = 0, D = 0, V = 0, Q = 0, C = 0, R = 0;
  bool S = false;
  // Q split by effect: shadow = lights, reflection = lights + 1, refraction = lights + 4 (0 where
  // the material lacks the effect), or measured rays per pixel when supplied. Q = their sum.
  std::array<double, kEffectCount> q{};
  std::array<bool, kEffectCount> Se{};  // effect selected last frame
};

struct HeuristicNode {
  int id = -1;
  double cost = 0, relevancy = 0;
};

// Phase 3 of §3.2: returns the ids of the selected nodes in selection order; the sum of their
// costs never exceeds `budget`.
std::vector<int> selectWithinBudget(std::vector<HeuristicNode> nodes, double budget);

// Partial objects (ms-budget mode, beyond the paper): the most relevant node the walk left out
// and the share of its cost that the unspent budget `left` pays for, so one large object that
// does not fit whole is traced over part of its pixels instead of not at all. id -1: none.
struct PartialNode {
  int id = -1;
  double fraction = 0;  // (0, 1)
};
PartialNode partialNode(const std::vector<HeuristicNode>& nodes, const std::vector<int>& selected,
                        double left);

// The squared distance from the view centre (pixels) within which `object` has `fraction` of its
// visible pixels: the part of a partial object that is traced is the part nearest the centre (a
// contiguous region, the part the eye is on). `centreOf(x)` is the centre of the view holding
// column x. It is centralBins(centralHistogram(...)) / TD_HEURISTIC_BINS of the squared
// half-diagonal of the view holding column 0 (the GPU counts the same histogram).
double centralRadius2(const Buffer& objectId, int object, double fraction,
                      const std::function<Vec2(int)>& centreOf);
// The object's pixels counted by squared distance to their view's centre over that
// half-diagonal, in TD_HEURISTIC_BINS bins (the last holding everything beyond).
std::vector<uint32_t> centralHistogram(const Buffer& objectId, int object,
                                       const std::function<Vec2(int)>& centreOf);
// The bins whose pixels together stay within `fraction` of the histogram's (all of them: its
// size).
int centralBins(const std::vector<uint32_t>& hist, double fraction);

// P of §3.2: 1 at the view centre falling to 0.01 at (and beyond) the edge, from NDC x, y.
double centreWeight(double ndcX, double ndcY);

// Phase 2 of §3.2 for every visible object (A > 0). `pixelCounts[o]` is object o's visible area;
// `selectedLast[o]` has bit e set when effect e of object o was selected last frame (S is any
// bit). `raysPerPixel`, when given, replaces the paper's q_e wherever it is positive.
std::vector<ObjectHeuristic> evaluateObjects(
    const Scene& scene, const std::vector<Bounds3>& worldBounds, const Camera& cam,
    const std::vector<uint32_t>& pixelCounts, const std::vector<uint8_t>& selectedLast,
    double importanceI,
    const std::vector<std::array<double, kEffectCount>>* raysPerPixel = nullptr);

// The graph's nodes: one per object (cost C, relevancy R; id = object) or, per effect, one per
// (object, effect) with cost A q_e E and relevancy (S_e I + V) K (id = object * 3 + effect).
// `costPerPixel[o][e]`, when given, replaces q_e as the cost of one visible pixel (the ms budget
// passes measured CPU ms per pixel, so costs are predicted milliseconds). `shadowsApart`: shadows
// are not the budget's (classified shadows trace them everywhere): nodes price only reflections
// and refractions, and objects with neither get no node.
std::vector<HeuristicNode> heuristicNodes(
    const Scene& scene, const std::vector<ObjectHeuristic>& objects, bool perEffect,
    double importanceI, const std::vector<std::array<double, kEffectCount>>* costPerPixel = nullptr,
    bool shadowsApart = false);

// Visible pixels per object in an object-id buffer (one parallel pass).
std::vector<uint32_t> countObjectPixels(const Buffer& objectId, size_t objectCount);

// Turns a budget in ms into cost units from the RT pass's measured time for the cost it was
// given. The rate is the median of the last three frames' cost / ms: one frame the OS stalls
// (or one mispriced object) does not halve the next frame's budget, and a real change is
// followed within two frames. The heuristic's ms-budget costs are predicted CPU ms, so the rate
// is the RT pass's effective parallelism (CPU ms per wall ms), and its prior the worker count.
class BudgetCalibration {
 public:
  // Rays per CPU ms assumed before any effect has been measured (about this machine).
  static constexpr double kPriorRaysPerMs = 10000;
  // The lowest rate learned, as a share of the prior.
  static constexpr double kFloor = 1e-3;
  explicit BudgetCalibration(double priorUnitsPerMs = 1) : prior_(priorUnitsPerMs) {}
  void observe(double selectedCost, double ms);
  double unitsFor(double budgetMs) const { return budgetMs * unitsPerMs(); }
  double unitsPerMs() const;

 private:
  double prior_;
  std::array<double, 3> samples_{};
  int count_ = 0;  // samples observed (the ring holds the last three)
};

struct HeuristicSettings {
  // Budget: a selected object's shadows are traced with it, within T (Walewski et al. 2019).
  // All: every visible object's shadows traced (classified shadows), T left to reflections and
  // refractions. Maps: no shadow traced, all from the shadow maps (deferred shading's or
  // ss_fallback's), T spent on reflections and refractions alone (where a stand-in differs most
  // from the rays).
  enum class Shadows { Budget, All, Maps };
  double budget = 2e6;       // T (cost units)
  double importance = 1000;  // I
  bool selectAll = false;
  Shadows shadows = Shadows::Budget;
  double budgetMs = 0;
  bool perEffect = false;
  bool partialObjects = false;
  bool countRecursion = false;
  bool deadline = false;
  double overcommit = 1.6;
};

// The counters HeuristicPass reports each frame (Pass::counters, FrameContext::report).
struct HeuristicCounters {
  static constexpr const char* selected = "heuristic/selected";
  static constexpr const char* nodes = "heuristic/nodes";
  static constexpr const char* visibleObjects = "heuristic/visible_objects";
  static constexpr const char* budget = "heuristic/budget";
  static constexpr const char* selectedCost = "heuristic/selected_cost";
  static constexpr const char* partialFraction = "heuristic/partial_fraction";
};

class HeuristicPass : public SettingsPass<HeuristicSettings> {
 public:
  // Slots, named once: inputs() and outputs() declare them, execute() binds them.
  struct Slots {
    static constexpr const char* heuristicMask = "heuristic_mask";
    static constexpr const char* heuristicOrder = "heuristic_order";
    static constexpr const char* objectId = "object_id";
    static constexpr const char* rtRequest = "rt_request";
    static constexpr const char* rtStats = "rt_stats";
  };
  std::string type() const override { return "heuristic"; }
  // Shadows it selects are traced and taken from deferred shading's unshadowed light.
  bool addsShadows() const override {
    return settings().shadows != HeuristicSettings::Shadows::Maps;
  }
  std::string description() const override {
    return "Per-object relevancy/cost selection under budget T (Walewski et al. 2019 §3.2)";
  }
  std::vector<BufferSlot> inputs() const override {
    return {{Slots::objectId, 1, BufferKind::Id}, rtStatsSlot(true)};
  }
  std::vector<BufferSlot> outputs() const override {
    return {effectSlot(Slots::heuristicMask, BufferKind::Mask), rtRequestSlot(false),
            effectSlot(Slots::heuristicOrder, BufferKind::List, Extent::any())};
  }
  void execute(FrameContext& ctx) override;
  // On the GPU the per-pixel halves (each object's area by atomics, the mask; a partial object's
  // pixels by distance from the centre); the selection between them on the host.
  bool hasGpu() const override { return true; }  // shaders/heuristic.comp
  void executeGpu(FrameContext& ctx) override;
  std::vector<CounterDesc> counters() const override;
  void resetHistory() override;

  const std::vector<ObjectHeuristic>& lastEvaluation() const { return evaluated_; }
  // Selected node ids (objects, or object * 3 + effect with per_effect).
  const std::vector<int>& lastSelection() const { return selected_; }
  double lastBudget() const { return budget_; }                // T used this frame (cost units)
  double lastSelectedCost() const { return selectedCost_; }    // sum of the selected costs
  const PartialNode& lastPartial() const { return partial_; }  // partial_objects: the part

 protected:
  const ParamTable<HeuristicSettings>& tableFor() const override;

 private:
  // A partial object's traced part: centralBins of the object's centralHistogram for the share.
  using CentralCut = std::function<int(int object, double fraction)>;
  void refreshBounds(const FrameContext& ctx);
  // The frame's selection from each object's visible pixels: the effect bits per object;
  // heuristic_order, rt_request and the counters written.
  std::vector<uint8_t> decide(FrameContext& ctx, const std::vector<uint32_t>& pixels,
                              const CentralCut& cut);
  // The nodes to choose from; with a ms budget priced in predicted CPU ms.
  std::vector<HeuristicNode> priceNodes(const Scene& scene, const std::vector<uint32_t>& pixels);
  // Chooses within budget_ (and the partial node); returns the effect bits per object.
  std::vector<uint8_t> select(const FrameContext& ctx, const std::vector<HeuristicNode>& nodes,
                              const CentralCut& cut);
  void writeMask(const FrameContext& ctx, const Buffer& ids, const std::vector<uint8_t>& selected,
                 Buffer& mask) const;
  // The partial node's object, or -2 (no object id) when none.
  float partialObject() const { return partial_.id >= 0 ? float(nodeObject(partial_.id)) : -2.0f; }
  // The partial node's effect bits (its shadows left to the maps with shadows = maps).
  uint8_t partialBits() const;
  void updateMeasurements(const RtStats& stats);
  // A node's object and effect bits (a node is an object, or object * 3 + effect with
  // per_effect).
  size_t nodeObject(int id) const { return size_t(settings().perEffect ? id / kEffectCount : id); }
  uint8_t nodeBits(int id) const {
    return settings().perEffect ? uint8_t(1u << (id % kEffectCount))
                                : uint8_t((1u << kEffectCount) - 1);
  }
  double tracedCost(const RtStats& stats) const;
  void writeOrder(const std::vector<HeuristicNode>& nodes, bool perEffect, Buffer& order) const;

  std::vector<uint8_t> selectedLast_;  // effect bits per object
  std::vector<ObjectHeuristic> evaluated_;
  std::vector<int> selected_;
  std::vector<Bounds3> bounds_;
  uint64_t boundsVersion_ = ~0ull;
  std::vector<std::array<double, kEffectCount>> measuredRays_;
  BudgetCalibration calibration_;
  bool calibrationPrior_ = false;  // prior set to the worker count on first use
  std::vector<std::array<double, kEffectCount>> msPerPixel_;  // measured, smoothed
  // Deadline mode: last frame's price of one traced pixel of each object and effect (cost units),
  // for the cost of what rt_secondary actually traced.
  std::vector<std::array<double, kEffectCount>> pricePerPixel_;
  double budget_ = 0, selectedCost_ = 0;
  PartialNode partial_;
  int partialBins_ = -1;  // the partial part's centralBins (-1: none)
  int64_t selectedFrame_ = -1;
};

}  // namespace tandem
