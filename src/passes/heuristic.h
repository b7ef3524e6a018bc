// heuristic: seed 002 §3.2. Every frame, for every object: visible area A (pixel count from the
// object-id buffer, one pass over the image), P (projected bounding-box centre, [0.01, 1]),
// D (distance to the camera), V = A P / D (eq. 1), Q (lights; + lights + 1 if reflective;
// + lights + 4 if refractive), S (selected last frame), C = A Q E (eq. 2), R = (S I + V) K (eq. 3).
// Then phase 3: nodes sorted by cost, each pointing to cheaper-or-equal, more relevant nodes,
// walked while budget T remains. Output: the per-pixel heuristic mask (Figure 2h).
// Input: object_id. Output: heuristic_mask. Parameters: budget (T), importance (I), select_all.
#pragma once
#include <cstdint>
#include <vector>

#include "core/buffer.h"
#include "pipeline/pass.h"
#include "scene/camera.h"
#include "scene/frame_scene.h"

namespace tandem {

struct ObjectHeuristic {
  int object = -1;
  double A = 0, P = 0, D = 0, V = 0, Q = 0, C = 0, R = 0;
  bool S = false;
};

struct HeuristicNode {
  int id = -1;
  double cost = 0, relevancy = 0;
};

// Phase 3 of §3.2: returns the ids of the selected nodes in selection order; the sum of their
// costs never exceeds `budget`.
std::vector<int> selectWithinBudget(std::vector<HeuristicNode> nodes, double budget);

// P of §3.2: 1 at the view centre falling to 0.01 at (and beyond) the edge, from NDC x, y.
double centreWeight(double ndcX, double ndcY);

// Phase 2 of §3.2 for every visible object (A > 0). `pixelCounts[o]` is object o's visible area.
std::vector<ObjectHeuristic> evaluateObjects(const Scene& scene,
                                             const std::vector<Bounds3>& worldBounds,
                                             const Camera& cam,
                                             const std::vector<uint32_t>& pixelCounts,
                                             const std::vector<uint8_t>& selectedLastFrame,
                                             double importanceI);

// Visible pixels per object in an object-id buffer (one parallel pass).
std::vector<uint32_t> countObjectPixels(const Buffer& objectId, size_t objectCount);

class HeuristicPass : public Pass {
 public:
  std::string type() const override { return "heuristic"; }
  std::string description() const override {
    return "Per-object relevancy/cost selection under budget T (seed 002 §3.2)";
  }
  std::vector<BufferSlot> inputs() const override { return {{"object_id", 1}}; }
  std::vector<BufferSlot> outputs() const override { return {{"heuristic_mask", 1}}; }
  std::vector<ParamDesc> params() const override;
  void execute(FrameContext& ctx) override;

  const std::vector<ObjectHeuristic>& lastEvaluation() const { return evaluated_; }
  const std::vector<int>& lastSelection() const { return selected_; }

 private:
  std::vector<uint8_t> selectedLast_;
  std::vector<ObjectHeuristic> evaluated_;
  std::vector<int> selected_;
  std::vector<Bounds3> bounds_;
  uint64_t boundsVersion_ = ~0ull;
};

}  // namespace tandem
