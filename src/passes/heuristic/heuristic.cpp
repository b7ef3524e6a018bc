#include "passes/heuristic/heuristic.h"

#include <tbb/combinable.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "gpu/shaders/heuristic_args.h"
#include "gpu/shaders/heuristic_spv.h"
#include "pipeline/frame_context.h"
#include "pipeline/gpu_frame.h"

namespace tandem {

std::vector<int> selectWithinBudget(std::vector<HeuristicNode> nodes, double budget) {
  // The graph: nodes by cost, descending (ties keep their input order). Every node "points to"
  // the nodes after it, which cost no more; those with higher relevancy are its candidates.
  std::stable_sort(nodes.begin(), nodes.end(),
                   [](const HeuristicNode& a, const HeuristicNode& b) { return a.cost > b.cost; });
  std::vector<int> selected;
  double left = budget;
  while (left > 0 && !nodes.empty()) {
    const HeuristicNode& cur = nodes.front();
    if (cur.cost > left) {  // cannot afford: not selected this frame, leaves the graph
      nodes.erase(nodes.begin());
      continue;
    }
    // The most relevant cheaper-or-equal node, if more relevant than the current one.
    size_t pick = 0;
    for (size_t i = 1; i < nodes.size(); ++i)
      if (nodes[i].relevancy > nodes[pick].relevancy) pick = i;
    selected.push_back(nodes[pick].id);
    left -= nodes[pick].cost;
    nodes.erase(nodes.begin() + std::ptrdiff_t(pick));
  }
  return selected;
}

PartialNode partialNode(const std::vector<HeuristicNode>& nodes, const std::vector<int>& selected,
                        double left) {
  PartialNode best;
  if (!(left > 0)) return best;
  double relevancy = -1;
  for (const HeuristicNode& n : nodes) {
    if (n.cost <= left || std::find(selected.begin(), selected.end(), n.id) != selected.end())
      continue;  // affordable nodes the walk skipped were less relevant than what it took
    if (n.relevancy > relevancy) {
      relevancy = n.relevancy;
      best = {n.id, left / n.cost};
    }
  }
  return best;
}

std::vector<uint32_t> centralHistogram(const Buffer& objectId, int object,
                                       const std::function<Vec2(int)>& centreOf) {
  // The object's pixels by squared distance to their view's centre, normalised by the squared
  // half-diagonal of the view holding column 0 (TD_HEURISTIC_BINS bins).
  constexpr int kBins = int(TD_HEURISTIC_BINS);
  const Vec2 c0 = centreOf(0);
  const double norm = double(c0.x) * c0.x + double(c0.y) * c0.y;
  std::vector<uint32_t> hist(kBins, 0);
  for (int y = 0; y < objectId.height; ++y)
    for (int x = 0; x < objectId.width; ++x) {
      if (objectId.at(x, y)[0] != float(object)) continue;
      const Vec2 c = centreOf(x);
      const double dx = x + 0.5 - c.x, dy = y + 0.5 - c.y;
      hist[size_t(std::min(int((dx * dx + dy * dy) / norm * kBins), kBins - 1))]++;
    }
  return hist;
}

int centralBins(const std::vector<uint32_t>& hist, double fraction) {
  uint32_t total = 0;
  for (uint32_t c : hist) total += c;
  const double want = fraction * total;
  uint32_t sum = 0;
  for (size_t b = 0; b < hist.size(); ++b) {
    if (sum + hist[b] > want) return int(b);
    sum += hist[b];
  }
  return int(hist.size());
}

double centralRadius2(const Buffer& objectId, int object, double fraction,
                      const std::function<Vec2(int)>& centreOf) {
  const Vec2 c0 = centreOf(0);
  const double norm = double(c0.x) * c0.x + double(c0.y) * c0.y;
  const int bins = centralBins(centralHistogram(objectId, object, centreOf), fraction);
  return double(bins) / TD_HEURISTIC_BINS * norm;
}

double centreWeight(double x, double y) {
  return std::max(1.0 - std::sqrt(x * x + y * y), 0.0) * 0.99 + 0.01;
}

std::vector<uint32_t> countObjectPixels(const Buffer& objectId, size_t objectCount) {
  tbb::combinable<std::vector<uint32_t>> counts(
      [&] { return std::vector<uint32_t>(objectCount, 0); });
  parallelRange(
      objectId.pixelCount(),
      [&](size_t b, size_t e) {
        auto& c = counts.local();
        for (size_t i = b; i < e; ++i) {
          float id = objectId.data[i];
          if (id >= 0 && size_t(id) < objectCount) ++c[size_t(id)];
        }
      },
      1 << 14);
  std::vector<uint32_t> total(objectCount, 0);
  counts.combine_each([&](const std::vector<uint32_t>& c) {
    for (size_t o = 0; o < objectCount; ++o) total[o] += c[o];
  });
  return total;
}

std::vector<ObjectHeuristic> evaluateObjects(
    const Scene& scene, const std::vector<Bounds3>& bounds, const Camera& cam,
    const std::vector<uint32_t>& pixels, const std::vector<uint8_t>& selectedLast, double I,
    const std::vector<std::array<double, kEffectCount>>* raysPerPixel) {
  std::vector<ObjectHeuristic> out;
  const double lights = double(scene.lights.size());
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    if (pixels[o] == 0) continue;  // not visible: rejected
    const Material& m = scene.materials[scene.objects[o].material];
    const HeuristicParams& hp = scene.objects[o].heuristic;
    ObjectHeuristic h;
    h.object = int(o);
    h.A = pixels[o];
    Vec3 centre = bounds[o].center();
    Vec4 clip = cam.viewProjUnjittered * Vec4(centre, 1.0f);
    h.P = clip.w > 1e-8f ? centreWeight(clip.x / clip.w, clip.y / clip.w) : 0.01;
    h.D = std::max(double(length(centre - cam.desc.position)), 1e-6);
    h.V = h.A * h.P / h.D;  // eq. 1
    h.q[kShadow] = lights;
    h.q[kReflection] = m.reflectivity > 0 ? lights + 1 : 0;
    h.q[kRefraction] = m.opacity < 1 ? lights + 4 : 0;
    const uint8_t last = o < selectedLast.size() ? selectedLast[o] : 0;
    h.Q = 0;
    for (int e = 0; e < kEffectCount; ++e) {
      // Measured rays replace the prior only where the effect applies at all.
      if (raysPerPixel && h.q[e] > 0 && (*raysPerPixel)[o][e] > 0) h.q[e] = (*raysPerPixel)[o][e];
      h.Q += h.q[e];
      h.Se[e] = (last >> e) & 1;
    }
    h.S = last != 0;
    h.C = h.A * h.Q * hp.E;                // eq. 2
    h.R = ((h.S ? I : 0.0) + h.V) * hp.K;  // eq. 3
    out.push_back(h);
  }
  return out;
}

std::vector<HeuristicNode> heuristicNodes(
    const Scene& scene, const std::vector<ObjectHeuristic>& objects, bool perEffect, double I,
    const std::vector<std::array<double, kEffectCount>>* costPerPixel, bool shadowsApart) {
  std::vector<HeuristicNode> nodes;
  for (const ObjectHeuristic& h : objects) {
    const HeuristicParams& hp = scene.objects[size_t(h.object)].heuristic;
    // Cost of effect e: A q_e E (eq. 2 split by effect), or A E x the given cost per pixel.
    auto cost = [&](int e) {
      if (h.q[size_t(e)] <= 0) return 0.0;
      double perPixel =
          costPerPixel ? (*costPerPixel)[size_t(h.object)][size_t(e)] : h.q[size_t(e)];
      return h.A * perPixel * hp.E;
    };
    if (shadowsApart && h.q[kReflection] <= 0 && h.q[kRefraction] <= 0) continue;
    if (!perEffect) {
      const double c = shadowsApart   ? cost(kReflection) + cost(kRefraction)
                       : costPerPixel ? cost(0) + cost(1) + cost(2)
                                      : h.C;
      nodes.push_back({h.object, c, h.R});
      continue;
    }
    for (int e = shadowsApart ? 1 : 0; e < kEffectCount; ++e)
      if (h.q[size_t(e)] > 0)
        nodes.push_back(
            {h.object * kEffectCount + e, cost(e), ((h.Se[size_t(e)] ? I : 0.0) + h.V) * hp.K});
  }
  return nodes;
}

void BudgetCalibration::observe(double selectedCost, double ms) {
  if (!(selectedCost > 0) || !(ms > 0)) return;  // nothing traced: nothing learned
  // A budget below the RT pass's fixed cost (its shadow maps, its launch) is never met: each frame
  // the rate falls by budget / time. Without a floor it would reach zero, where no budget raised
  // later buys anything again.
  samples_[size_t(count_ % 3)] = std::max(selectedCost / ms, kFloor * prior_);
  ++count_;
}

double BudgetCalibration::unitsPerMs() const {
  if (count_ == 0) return prior_;
  if (count_ == 1) return samples_[0];
  if (count_ == 2) return 0.5 * (samples_[0] + samples_[1]);
  std::array<double, 3> s = samples_;
  std::sort(s.begin(), s.end());
  return s[1];
}

const ParamTable<HeuristicSettings>& HeuristicPass::tableFor() const {
  using S = HeuristicSettings;
  static const ParamTable<S> table =
      ParamTable<S>()
          .add(&S::budget,
               {.name = "budget",
                .min = 0,
                .max = 1e15,
                .doc = "T: ray-tracing budget in cost units (visible pixels x rays x E)"})
          .add(&S::importance,
               {.name = "importance",
                .min = 0,
                .max = 1e12,
                .doc = "I: relevancy bonus for objects selected last frame (stability)"})
          .add(&S::selectAll,
               {.name = "select_all", .doc = "select every visible object (no heuristic)"})
          .add(&S::shadows,
               {.name = "shadows",
                .doc = "shadows: selected with their object within the budget (Walewski et al. "
                       "2019); every visible object's traced (classified shadows), the budget "
                       "left to reflections and refractions; or none traced, all from the "
                       "shadow maps (deferred_shading's or ss_fallback's), the whole budget for "
                       "reflections and refractions",
                .choices = {"budget", "all", "maps"}})
          .add(&S::budgetMs,
               {.name = "budget_ms",
                .min = 0,
                .max = 1e6,
                .doc = "RT budget in ms; T is calibrated from measured RT time (0 = use budget)"})
          .add(&S::perEffect,
               {.name = "per_effect",
                .doc = "select shadows, reflections, refractions separately per object"})
          .add(&S::partialObjects, {.name = "partial_objects",
                                    .doc = "ms budget: spend what is left on the central part of "
                                           "the next object that does not fit"})
          .add(&S::countRecursion,
               {.name = "count_recursion",
                .doc = "cost from the rays actually traced per pixel, recursion included"})
          .add(&S::deadline,
               {.name = "deadline",
                .doc = "ms budget: rt_secondary stops at the budget, most relevant pixels first"})
          .add(&S::overcommit, {.name = "overcommit",
                                .min = 1,
                                .max = 4,
                                .doc = "deadline: select this many times the budget (the deadline "
                                       "cuts the least relevant)"});
  return table;
}

double HeuristicPass::tracedCost(const RtStats& stats) const {
  double cost = 0;
  for (size_t o = 0; o < std::min(stats.pixels.size(), pricePerPixel_.size()); ++o)
    for (size_t e = 0; e < size_t(kEffectCount); ++e)
      cost += double(stats.pixels[o][e]) * pricePerPixel_[o][e];
  return cost;
}

void HeuristicPass::writeOrder(const std::vector<HeuristicNode>& nodes, bool perEffect,
                               Buffer& order) const {
  std::vector<double> relevancy(order.data.size(), 0.0);
  for (const HeuristicNode& node : nodes) relevancy[size_t(node.id)] = node.relevancy;
  std::vector<HeuristicNode> chosen;
  for (int id : selected_) chosen.push_back({id, 0.0, relevancy[size_t(id)]});
  std::stable_sort(
      chosen.begin(), chosen.end(),
      [](const HeuristicNode& a, const HeuristicNode& b) { return a.relevancy > b.relevancy; });
  std::fill(order.data.begin(), order.data.end(), -1.0f);
  for (size_t r = 0; r < chosen.size(); ++r) {
    const int id = chosen[r].id;
    if (perEffect)
      order.data[size_t(id)] = float(r);  // id = object * kEffectCount + effect
    else
      for (int e = 0; e < kEffectCount; ++e) order.data[size_t(id * kEffectCount + e)] = float(r);
  }
}

void HeuristicPass::resetHistory() {
  selectedLast_.clear();
  selectedFrame_ = -1;
}

void HeuristicPass::updateMeasurements(const RtStats& stats) {
  // Each frame's RT figures (last frame's history value, seen once) are folded in: ½ old + ½ new
  // (the first taken as is).
  if (stats.ms <= 0) return;  // the RT pass did not run (bypassed, or no history)
  auto fold = [](double& m, double v) { m = m > 0 ? 0.5 * m + 0.5 * v : v; };
  msPerPixel_.resize(stats.pixels.size());
  measuredRays_.resize(stats.pixels.size());
  for (size_t o = 0; o < stats.pixels.size(); ++o)
    for (size_t e = 0; e < size_t(kEffectCount); ++e) {
      const double pixels = double(stats.pixels[o][e]);
      if (pixels == 0) continue;
      fold(measuredRays_[o][e], double(stats.rays[o][e]) / pixels);
      // Time only when the RT pass was asked to measure it (ms budget).
      if (o < stats.cpuMs.size() && stats.cpuMs[o][e] > 0)
        fold(msPerPixel_[o][e], stats.cpuMs[o][e] / pixels);
    }
}

namespace {
// The centre (pixels) of the view that holds frame column x.
Vec2 viewCentre(const FrameContext& ctx, int x) {
  for (const View& v : ctx.views)
    if (x >= v.x && x < v.x + v.camera.width)
      return {float(v.x) + 0.5f * float(v.camera.width),
              float(v.y) + 0.5f * float(v.camera.height)};
  return {0.5f * float(ctx.width), 0.5f * float(ctx.height)};
}

// The squared half-diagonal of the view holding column 0: centralHistogram's unit.
double viewNorm(const FrameContext& ctx) {
  const Vec2 c0 = viewCentre(ctx, 0);
  return double(c0.x) * c0.x + double(c0.y) * c0.y;
}
}  // namespace

void HeuristicPass::refreshBounds(const FrameContext& ctx) {
  const size_t n = ctx.scene->objects.size();
  if (boundsVersion_ != ctx.frame.geometryVersion || bounds_.size() != n) {
    bounds_.assign(n, Bounds3{});
    for (size_t o = 0; o < n; ++o)
      for (const Vec3& p : ctx.frame.objects[o].positions) bounds_[o].extend(p);
    boundsVersion_ = ctx.frame.geometryVersion;
  }
}

std::vector<HeuristicNode> HeuristicPass::priceNodes(const Scene& scene,
                                                     const std::vector<uint32_t>& pixels) {
  const HeuristicSettings& s = settings();
  const bool shadowsApart = s.shadows != HeuristicSettings::Shadows::Budget;
  if (s.budgetMs <= 0)
    return heuristicNodes(scene, evaluated_, s.perEffect, s.importance, nullptr, shadowsApart);
  // Objects and effects not measured yet are priced at the mean measured cost per pixel of that
  // effect over the visible objects (weighted by area), or at the prior ray rate.
  const size_t n = scene.objects.size();
  msPerPixel_.resize(n);
  std::array<double, kEffectCount> sum{}, area{};
  for (size_t o = 0; o < n; ++o)
    for (size_t e = 0; e < size_t(kEffectCount); ++e)
      if (msPerPixel_[o][e] > 0) {
        sum[e] += msPerPixel_[o][e] * pixels[o];
        area[e] += pixels[o];
      }
  std::vector<std::array<double, kEffectCount>> perPixel = msPerPixel_;
  for (const ObjectHeuristic& h : evaluated_)
    for (size_t e = 0; e < size_t(kEffectCount); ++e) {
      double& p = perPixel[size_t(h.object)][e];
      if (p <= 0) p = area[e] > 0 ? sum[e] / area[e] : h.q[e] / BudgetCalibration::kPriorRaysPerMs;
    }
  std::vector<HeuristicNode> nodes =
      heuristicNodes(scene, evaluated_, s.perEffect, s.importance, &perPixel, shadowsApart);
  pricePerPixel_.assign(n, {});
  for (const ObjectHeuristic& h : evaluated_)
    for (size_t e = 0; e < size_t(kEffectCount); ++e)
      pricePerPixel_[size_t(h.object)][e] =
          perPixel[size_t(h.object)][e] * scene.objects[size_t(h.object)].heuristic.E;
  return nodes;
}

std::vector<uint8_t> HeuristicPass::select(const FrameContext& ctx,
                                           const std::vector<HeuristicNode>& nodes,
                                           const CentralCut& cut) {
  const HeuristicSettings& s = settings();
  const size_t n = ctx.scene->objects.size();
  const bool perEffect = s.perEffect, msBudget = s.budgetMs > 0;
  budget_ = msBudget ? calibration_.unitsFor(s.budgetMs) : s.budget;
  if (msBudget && s.deadline) budget_ *= s.overcommit;
  if (s.selectAll) {
    selected_.clear();
    for (const HeuristicNode& node : nodes) selected_.push_back(node.id);
  } else {
    selected_ = selectWithinBudget(nodes, budget_);
  }
  std::vector<double> costOf(perEffect ? n * kEffectCount : n, 0.0);
  for (const HeuristicNode& node : nodes) costOf[size_t(node.id)] = node.cost;
  std::vector<uint8_t> selected(n, 0);  // effect bits per object
  selectedCost_ = 0;
  for (int id : selected_) {
    selectedCost_ += costOf[size_t(id)];
    selected[nodeObject(id)] |= nodeBits(id);
  }
  partial_ = {};
  partialBins_ = -1;
  if (msBudget && s.partialObjects && !s.selectAll) {
    partial_ = partialNode(nodes, selected_, budget_ - selectedCost_);
    if (partial_.id >= 0) {
      selectedCost_ += partial_.fraction * costOf[size_t(partial_.id)];
      partialBins_ = cut(int(nodeObject(partial_.id)), partial_.fraction);
    }
  }
  if (s.shadows == HeuristicSettings::Shadows::All)
    for (const ObjectHeuristic& h : evaluated_) selected[size_t(h.object)] |= 1u << kShadow;
  if (s.shadows == HeuristicSettings::Shadows::Maps)  // (the nodes priced without them)
    for (uint8_t& bits : selected) bits &= uint8_t(~(1u << kShadow));
  return selected;
}

uint8_t HeuristicPass::partialBits() const {
  uint8_t bits = partial_.id >= 0 ? nodeBits(partial_.id) : 0;
  if (settings().shadows == HeuristicSettings::Shadows::Maps) bits &= uint8_t(~(1u << kShadow));
  return bits;
}

void HeuristicPass::writeMask(const FrameContext& ctx, const Buffer& ids,
                              const std::vector<uint8_t>& selected, Buffer& mask) const {
  const float partialObject = this->partialObject();
  const uint8_t partialBits = this->partialBits();
  const double partialR2 =
      partialBins_ >= 0 ? double(partialBins_) / TD_HEURISTIC_BINS * viewNorm(ctx) : -1.0;
  parallelRange(
      mask.pixelCount(),
      [&](size_t b, size_t e) {
        for (size_t i = b; i < e; ++i) {
          float id = ids.data[i];
          uint8_t bits = id >= 0 ? selected[size_t(id)] : 0;
          if (id == partialObject) {
            const int x = int(i % size_t(ids.width)), y = int(i / size_t(ids.width));
            const Vec2 c = viewCentre(ctx, x);
            const double dx = x + 0.5 - c.x, dy = y + 0.5 - c.y;
            if (dx * dx + dy * dy < partialR2) bits |= partialBits;
          }
          for (int k = 0; k < kEffectCount; ++k)
            mask.data[i * kEffectCount + size_t(k)] = float((bits >> k) & 1);
        }
      },
      1 << 14);
}

std::vector<CounterDesc> HeuristicPass::counters() const {
  return {
      {HeuristicCounters::selected, "nodes chosen for ray tracing this frame"},
      {HeuristicCounters::nodes,
       "candidate nodes (objects, or object-effect pairs with per_effect)"},
      {HeuristicCounters::visibleObjects, "objects evaluated (visible in some view)"},
      {HeuristicCounters::budget, "the ray budget the selection filled"},
      {HeuristicCounters::selectedCost, "estimated cost of the selected nodes"},
      {HeuristicCounters::partialFraction,
       "share of the partially selected node that is traced (0 when none)"},
  };
}

std::vector<uint8_t> HeuristicPass::decide(FrameContext& ctx, const std::vector<uint32_t>& pixels,
                                           const CentralCut& cut) {
  const HeuristicSettings& s = settings();
  const Scene& scene = *ctx.scene;
  const size_t n = scene.objects.size();
  refreshBounds(ctx);
  // Last frame's RT pass: its time for the cost we selected calibrates the ms budget.
  const RtStats* prevStats = ctx.previousRecord<RtStats>(*this, Slots::rtStats);
  const RtStats rtStats = prevStats ? *prevStats : RtStats{};
  // With a ms budget, costs are predicted CPU ms and T is in CPU ms (the calibration's rate is
  // CPU ms per wall ms of the RT pass; its prior, the worker count).
  const bool msBudget = s.budgetMs > 0;
  const bool deadline = msBudget && s.deadline;
  if (rtStats.ms > 0 && selectedFrame_ >= 0 && selectedFrame_ == ctx.serial - 1)
    calibration_.observe(deadline ? tracedCost(rtStats) : selectedCost_, rtStats.ms);
  updateMeasurements(rtStats);
  measuredRays_.resize(n);

  selectedLast_.resize(n, 0);
  evaluated_ = evaluateObjects(scene, bounds_, ctx.camera(), pixels, selectedLast_, s.importance,
                               s.countRecursion ? &measuredRays_ : nullptr);
  // This frame's RT pass times each object and effect.
  RtRequest& request = ctx.outputRecord<RtRequest>(*this, Slots::rtRequest);
  request.timeEffects = msBudget;
  request.deadlineMs = deadline ? s.budgetMs : 0.0;
  if (!calibrationPrior_) {
    calibration_ = BudgetCalibration(double(tbb::this_task_arena::max_concurrency()));
    calibrationPrior_ = true;
  }
  const std::vector<HeuristicNode> nodes = priceNodes(scene, pixels);
  const std::vector<uint8_t> selected = select(ctx, nodes, cut);
  selectedFrame_ = ctx.serial;
  selectedLast_ = selected;
  // The partial node counts as selected for stability (I): it stays the one part-traced.
  if (partial_.id >= 0) selectedLast_[nodeObject(partial_.id)] |= nodeBits(partial_.id);
  // For experiments and the viewer: what was selected out of what (nodes: objects, or
  // object-effect pairs with per_effect).
  ctx.report(*this, HeuristicCounters::selected, double(selected_.size()));
  ctx.report(*this, HeuristicCounters::nodes, double(nodes.size()));
  ctx.report(*this, HeuristicCounters::visibleObjects, double(evaluated_.size()));
  ctx.report(*this, HeuristicCounters::budget, budget_);
  ctx.report(*this, HeuristicCounters::selectedCost, selectedCost_);
  ctx.report(*this, HeuristicCounters::partialFraction, partial_.id >= 0 ? partial_.fraction : 0.0);
  writeOrder(nodes, s.perEffect, ctx.output(*this, Slots::heuristicOrder, int(n), 1));
  return selected;
}

void HeuristicPass::execute(FrameContext& ctx) {
  const Buffer& ids = ctx.input(*this, Slots::objectId);
  const CentralCut cut = [&](int object, double fraction) {
    return centralBins(centralHistogram(ids, object, [&](int x) { return viewCentre(ctx, x); }),
                       fraction);
  };
  const std::vector<uint8_t> selected =
      decide(ctx, countObjectPixels(ids, ctx.scene->objects.size()), cut);
  writeMask(ctx, ids, selected, ctx.output(*this, Slots::heuristicMask));
}

void HeuristicPass::executeGpu(FrameContext& ctx) {
  GpuFrame& gpu = *ctx.gpu;
  GpuCommands& cmd = gpu.commands();
  const size_t n = ctx.scene->objects.size();
  const std::vector<uint32_t> zero(std::max<size_t>(n, 1), 0);
  HeuristicArgs a{};
  a.objectId = ctx.deviceInput(*this, Slots::objectId);
  a.pixels = gpu.constants(zero.data(), zero.size() * sizeof(uint32_t));
  a.pixelCount = uint32_t(size_t(ctx.width) * size_t(ctx.height));
  a.objectCount = uint32_t(n);
  a.width = uint32_t(ctx.width);
  a.partialObject = TD_HEURISTIC_NONE;
  // Each view's columns and twice its centre (integers: the distances compare exactly).
  std::vector<HeuristicView> views;
  for (const View& v : ctx.views)
    views.push_back({uint32_t(v.x), uint32_t(v.x + v.camera.width),
                     uint32_t(2 * v.x + v.camera.width), uint32_t(2 * v.y + v.camera.height)});
  views.push_back({0, uint32_t(ctx.width), uint32_t(ctx.width), uint32_t(ctx.height)});
  a.views = gpu.constants(views.data(), views.size() * sizeof(HeuristicView));
  a.viewCount = uint32_t(views.size());
  a.norm4 = uint32_t(4.0 * viewNorm(ctx));
  // A 2D grid: one invocation a pixel, rows of at most 65535 groups of 64.
  const uint32_t groups = (a.pixelCount + 63) / 64, gx = std::max(1u, std::min(groups, 65535u));
  a.rowWidth = gx * 64;
  const GpuKernel& k =
      gpu.kernel("heuristic", kHeuristicSpv, sizeof(kHeuristicSpv) / 4, sizeof(HeuristicArgs));
  a.mode = TD_HEURISTIC_COUNT;
  cmd.dispatch(k, gx, (groups + gx - 1) / gx, 1, &a);
  // The selection needs every object's area: the counts come back before the mask is recorded.
  cmd.checkpoint();
  const auto* counted = static_cast<const uint32_t*>(gpu.constantsData(a.pixels));
  // A partial object's pixels by distance, counted where they are, cut on the host.
  const CentralCut cut = [&](int object, double fraction) {
    HeuristicArgs h = a;
    const std::vector<uint32_t> empty(TD_HEURISTIC_BINS, 0);
    h.pixels = gpu.constants(empty.data(), empty.size() * sizeof(uint32_t));
    h.partialObject = uint32_t(object);
    h.mode = TD_HEURISTIC_CENTRAL;
    cmd.dispatch(k, gx, (groups + gx - 1) / gx, 1, &h);
    cmd.checkpoint();
    const auto* hist = static_cast<const uint32_t*>(gpu.constantsData(h.pixels));
    return centralBins(std::vector<uint32_t>(hist, hist + TD_HEURISTIC_BINS), fraction);
  };
  const std::vector<uint8_t> selected =
      decide(ctx, std::vector<uint32_t>(counted, counted + n), cut);
  std::vector<uint32_t> bits(std::max<size_t>(n, 1), 0);
  for (size_t o = 0; o < n; ++o) bits[o] = selected[o];
  a.selected = gpu.constants(bits.data(), bits.size() * sizeof(uint32_t));
  a.mask = ctx.deviceOutput(*this, Slots::heuristicMask);
  if (partialBins_ >= 0) {
    a.partialObject = uint32_t(nodeObject(partial_.id));
    a.partialBits = partialBits();
    a.partialBins = uint32_t(partialBins_);
  }
  a.mode = TD_HEURISTIC_MASK;
  cmd.dispatch(k, gx, (groups + gx - 1) / gx, 1, &a);
}

}  // namespace tandem
