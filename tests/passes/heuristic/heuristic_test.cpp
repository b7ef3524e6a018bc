#include <gtest/gtest.h>

#include <random>

#include "passes/heuristic/heuristic.h"
#include "scene/builtin_scenes.h"
#include "scene/primitives.h"

using namespace tandem;

// Walewski et al. 2019 Figure 4 with T = 400, values chosen to match the text: nodes 0-2 cost more
// than 400 and leave the graph; node 3 is the first affordable one and points to nodes 5 and 6 as
// more relevant (5 the more relevant), so 5 is taken first; the walk goes on while budget lasts.
TEST(Heuristic, Figure4WorkedExample) {
  std::vector<HeuristicNode> nodes = {{0, 900, 5}, {1, 700, 9}, {2, 500, 2}, {3, 350, 3},
                                      {4, 300, 1}, {5, 200, 8}, {6, 100, 6}, {7, 50, 2}};
  std::vector<int> sel = selectWithinBudget(nodes, 400);
  // 5 (200, left 200); 3 and 4 no longer fit; 6 (100, left 100); 7 (50, left 50).
  EXPECT_EQ(sel, (std::vector<int>{5, 6, 7}));
}

TEST(Heuristic, SelectedCostNeverExceedsBudget) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> cost(0, 1000), rel(0, 100), budget(0, 3000);
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<HeuristicNode> nodes;
    for (int i = 0; i < 1 + trial % 40; ++i) nodes.push_back({i, cost(rng), rel(rng)});
    double T = budget(rng);
    double sum = 0;
    for (int id : selectWithinBudget(nodes, T)) sum += nodes[size_t(id)].cost;
    EXPECT_LE(sum, T);
  }
}

TEST(Heuristic, MoreRelevantCheaperNodeWins) {
  // Only one of the two fits after the first pick: the more relevant one is taken.
  std::vector<int> sel = selectWithinBudget({{0, 100, 1}, {1, 90, 5}}, 120);
  EXPECT_EQ(sel, (std::vector<int>{1}));
}

TEST(Heuristic, CentreWeight) {
  EXPECT_DOUBLE_EQ(centreWeight(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(centreWeight(1, 0), 0.01);
  EXPECT_DOUBLE_EQ(centreWeight(3, 4), 0.01);
  EXPECT_NEAR(centreWeight(0.6, 0.8), 0.01, 1e-12);
  EXPECT_NEAR(centreWeight(0.5, 0), 0.5 * 0.99 + 0.01, 1e-12);
}

namespace {

// A plain object and a glass mirror, two lights, seen from +Z.
struct TwoObjects {
  Scene s;
  Camera cam;
  std::vector<Bounds3> bounds{2};
  TwoObjects() {
    int mesh = s.addMesh(makeCube());
    Material plain, glassMirror;
    glassMirror.reflectivity = 0.5f;
    glassMirror.opacity = 0.2f;
    s.addObject("a", mesh, s.addMaterial(plain));
    s.addObject("b", mesh, s.addMaterial(glassMirror));
    s.objects[1].heuristic = {2.0f, 3.0f};  // K, E
    s.lights.resize(2);
    CameraDesc cd;
    cd.position = {0, 0, 10};
    cd.lookAt = {0, 0, 0};
    cam = Camera::make(cd, 100, 100);
    bounds[0].extend({-1, -1, -1});
    bounds[0].extend({1, 1, 1});
    bounds[1].extend({4, -1, -1});  // centre (5, 0, 0), off to the right
    bounds[1].extend({6, 1, 1});
  }
};

}  // namespace

// Hand-computed eq. 1-3 for two objects: a plain one at the view centre and a glass mirror.
TEST(Heuristic, EquationsByHand) {
  TwoObjects t;
  const Scene& s = t.s;
  const Camera& cam = t.cam;
  const std::vector<Bounds3>& bounds = t.bounds;
  std::vector<ObjectHeuristic> h = evaluateObjects(s, bounds, cam, {400, 100}, {0, 1}, 50.0);
  ASSERT_EQ(h.size(), 2u);
  EXPECT_DOUBLE_EQ(h[0].A, 400);
  EXPECT_NEAR(h[0].P, 1.0, 1e-6);
  EXPECT_NEAR(h[0].D, 10.0, 1e-5);
  EXPECT_NEAR(h[0].V, 40.0, 1e-3);
  EXPECT_EQ(h[0].Q, 2);                      // lights only
  EXPECT_NEAR(h[0].C, 400 * 2 * 1.0, 1e-9);  // E = 1
  EXPECT_NEAR(h[0].R, 40.0, 1e-3);           // not selected last frame, K = 1
  EXPECT_EQ(h[1].Q, 2 + (2 + 1) + (2 + 4));  // reflective and refractive
  EXPECT_NEAR(h[1].C, 100 * 11 * 3.0, 1e-9);
  double ndcX = 5.0 / 10.0 / std::tan(radians(45.0f / 2));  // x / (z tan(fov/2)), aspect 1
  double P = centreWeight(ndcX, 0);
  EXPECT_NEAR(h[1].P, P, 1e-5);
  double D = std::sqrt(25.0 + 100.0);
  EXPECT_NEAR(h[1].R, (50.0 + 100 * P / D) * 2.0, 1e-3);
  // Invisible objects are rejected.
  EXPECT_TRUE(evaluateObjects(s, bounds, cam, {0, 0}, {0, 0}, 1.0).empty());
}

// Per-effect nodes: one per effect the material has, cost A q_e E, relevancy (S_e I + V) K.
TEST(Heuristic, PerEffectNodesByHand) {
  TwoObjects t;
  // Object b had only its reflection selected last frame (bit 1).
  std::vector<ObjectHeuristic> h =
      evaluateObjects(t.s, t.bounds, t.cam, {400, 100}, {0, 1u << kReflection}, 50.0);
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h[0].q, (std::array<double, 3>{2, 0, 0}));  // shadows only
  EXPECT_EQ(h[1].q, (std::array<double, 3>{2, 3, 6}));
  EXPECT_TRUE(h[1].Se[kReflection]);
  EXPECT_FALSE(h[1].Se[kShadow]);
  std::vector<HeuristicNode> nodes = heuristicNodes(t.s, h, true, 50.0);
  ASSERT_EQ(nodes.size(), 4u);  // a: shadow; b: shadow, reflection, refraction
  EXPECT_EQ(nodes[0].id, 0 * 3 + kShadow);
  EXPECT_DOUBLE_EQ(nodes[0].cost, 400 * 2 * 1.0);
  EXPECT_NEAR(nodes[0].relevancy, h[0].V, 1e-9);
  EXPECT_EQ(nodes[2].id, 1 * 3 + kReflection);
  EXPECT_DOUBLE_EQ(nodes[2].cost, 100 * 3 * 3.0);
  EXPECT_NEAR(nodes[2].relevancy, (50.0 + h[1].V) * 2.0, 1e-9);  // S_e = 1
  EXPECT_NEAR(nodes[3].relevancy, h[1].V * 2.0, 1e-9);           // refraction: S_e = 0
  EXPECT_DOUBLE_EQ(nodes[3].cost, 100 * 6 * 3.0);
  // The per-object costs are the sums of the per-effect ones.
  std::vector<HeuristicNode> whole = heuristicNodes(t.s, h, false, 50.0);
  ASSERT_EQ(whole.size(), 2u);
  EXPECT_DOUBLE_EQ(whole[1].cost, nodes[1].cost + nodes[2].cost + nodes[3].cost);
}

// Under a budget too small for the whole glass mirror, per-effect selection still gives it
// the effects that fit, where the paper's all-or-nothing selection gives it none.
TEST(Heuristic, PerEffectSelectionTakesWhatFits) {
  TwoObjects t;
  std::vector<ObjectHeuristic> h = evaluateObjects(t.s, t.bounds, t.cam, {400, 100}, {0, 0}, 0);
  double T = 100 * 5 * 3.0;  // b's shadow (600) fits, its shadow + reflection (1500) does not
  std::vector<int> whole = selectWithinBudget(heuristicNodes(t.s, h, false, 0), T);
  EXPECT_TRUE(std::find(whole.begin(), whole.end(), 1) == whole.end());
  std::vector<int> perEffect = selectWithinBudget(heuristicNodes(t.s, h, true, 0), T);
  EXPECT_TRUE(std::find(perEffect.begin(), perEffect.end(), 1 * 3 + kShadow) != perEffect.end());
  double sum = 0;
  for (const HeuristicNode& n : heuristicNodes(t.s, h, true, 0))
    if (std::find(perEffect.begin(), perEffect.end(), n.id) != perEffect.end()) sum += n.cost;
  EXPECT_LE(sum, T);
}

// Measured rays per pixel replace the paper's q_e only where the material has the effect.
TEST(Heuristic, MeasuredRaysReplaceThePrior) {
  TwoObjects t;
  std::vector<std::array<double, 3>> measured = {{1.5, 9, 9}, {2, 7.25, 0}};
  std::vector<ObjectHeuristic> h =
      evaluateObjects(t.s, t.bounds, t.cam, {400, 100}, {0, 0}, 0, &measured);
  EXPECT_EQ(h[0].q, (std::array<double, 3>{1.5, 0, 0}));   // a has no reflection/refraction
  EXPECT_EQ(h[1].q, (std::array<double, 3>{2, 7.25, 6}));  // not measured: prior lights + 4
  EXPECT_DOUBLE_EQ(h[1].Q, 2 + 7.25 + 6);
  EXPECT_DOUBLE_EQ(h[1].C, 100 * (2 + 7.25 + 6) * 3.0);
}

TEST(Heuristic, BudgetCalibrationIsTheMedianOfThreeFrames) {
  BudgetCalibration c(2.0);
  EXPECT_DOUBLE_EQ(c.unitsPerMs(), 2.0);  // the prior until something is measured
  c.observe(1000, 10);                    // 100 units/ms
  EXPECT_DOUBLE_EQ(c.unitsFor(5), 500);
  c.observe(3000, 10);  // two samples: their mean
  EXPECT_DOUBLE_EQ(c.unitsPerMs(), 200);
  c.observe(0, 10);  // nothing traced: nothing learned
  c.observe(100, 0);
  EXPECT_DOUBLE_EQ(c.unitsPerMs(), 200);
  c.observe(1000, 10);  // 100, 300, 100: median 100
  EXPECT_DOUBLE_EQ(c.unitsPerMs(), 100);
  c.observe(500, 10);  // one stalled frame (50) among 300, 100: ignored
  EXPECT_DOUBLE_EQ(c.unitsPerMs(), 100);
  c.observe(3000, 10);  // 100, 50, 300 -> 100; a lasting change wins within two frames
  c.observe(3000, 10);  // 50, 300, 300 -> 300
  EXPECT_DOUBLE_EQ(c.unitsPerMs(), 300);
}

// A budget below the RT pass's fixed cost (its shadow maps, its launch) is never met, and the rate
// falls while it lasts; a budget raised later is met again within 30 frames (the rate at the
// fixed point of cost = units * budget, time = overhead + cost / true rate).
TEST(Heuristic, BudgetCalibrationRecoversFromABudgetItCannotMeet) {
  const double overhead = 10, rate = 4;  // wall ms whatever is selected; units a traced wall ms
  BudgetCalibration c(2.0);
  const auto frame = [&](double budgetMs) {
    const double cost = c.unitsFor(budgetMs);  // the walk fills the budget
    c.observe(cost, overhead + cost / rate);
  };
  for (int f = 0; f < 300; ++f) frame(2);  // under the overhead
  EXPECT_LT(c.unitsPerMs(), 0.01);
  for (int f = 0; f < 30; ++f) frame(30);
  const double fixedPoint = rate * (30 - overhead) / 30;
  EXPECT_NEAR(c.unitsPerMs(), fixedPoint, 0.01 * fixedPoint);
}

// Partial objects: the unspent budget buys a share of the most relevant node left out (Figure 4:
// 5, 6, 7 take 350 of 400; of 0-4, node 1 is the most relevant, and 50 buys 50/700 of it).
TEST(Heuristic, PartialNodeIsTheMostRelevantLeftOut) {
  std::vector<HeuristicNode> nodes = {{0, 900, 5}, {1, 700, 9}, {2, 500, 2}, {3, 350, 3},
                                      {4, 300, 1}, {5, 200, 8}, {6, 100, 6}, {7, 50, 2}};
  std::vector<int> sel = selectWithinBudget(nodes, 400);
  PartialNode p = partialNode(nodes, sel, 400 - 350);
  EXPECT_EQ(p.id, 1);
  EXPECT_DOUBLE_EQ(p.fraction, 50.0 / 700.0);
  EXPECT_EQ(partialNode(nodes, sel, 0).id, -1);  // nothing left: no part
  // Everything selected: nothing to part-trace.
  std::vector<int> all = {0, 1, 2, 3, 4, 5, 6, 7};
  EXPECT_EQ(partialNode(nodes, all, 100).id, -1);
}

// The traced part is the share of the object's pixels nearest the view centre: on an object
// covering a whole 64 x 64 view, a quarter of its pixels is the disc of area 1024 around the
// centre (radius 18.05), to within the histogram's resolution.
TEST(Heuristic, PartialObjectIsItsCentralShare) {
  Buffer ids(64, 64, 1, 3.0f, BufferKind::Id);
  for (int x = 0; x < 8; ++x) ids.at(x, 0)[0] = 1.0f;  // a few pixels of another object
  auto centre = [](int) { return Vec2{32, 32}; };
  for (double f : {0.1, 0.25, 0.5}) {
    const double r2 = centralRadius2(ids, 3, f, centre);
    int inside = 0, total = 0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        if (ids.at(x, y)[0] != 3.0f) continue;
        ++total;
        const double dx = x + 0.5 - 32, dy = y + 0.5 - 32;
        inside += dx * dx + dy * dy < r2 ? 1 : 0;
      }
    EXPECT_LE(inside, f * total) << f;  // never more than the budget pays for
    EXPECT_GE(inside, 0.97 * f * total) << f;
    EXPECT_NEAR(r2, f * total / 3.14159265, 0.03 * f * total) << f;  // a disc
  }
  EXPECT_DOUBLE_EQ(centralRadius2(ids, 3, 0.0, centre), 0.0);
}
