#include <gtest/gtest.h>

#include <random>

#include "passes/heuristic.h"
#include "scene/builtin_scenes.h"
#include "scene/primitives.h"

using namespace tandem;

// Seed 002 Figure 4 with T = 400, values chosen to match the text: nodes 0-2 cost more than
// 400 and leave the graph; node 3 is the first affordable one and points to nodes 5 and 6 as
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

// Hand-computed eq. 1-3 for two objects: a plain one at the view centre and a glass mirror.
TEST(Heuristic, EquationsByHand) {
  Scene s;
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
  Camera cam = Camera::make(cd, 100, 100);
  std::vector<Bounds3> bounds(2);
  bounds[0].extend({-1, -1, -1});
  bounds[0].extend({1, 1, 1});
  bounds[1].extend({4, -1, -1});  // centre (5, 0, 0), off to the right
  bounds[1].extend({6, 1, 1});
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
