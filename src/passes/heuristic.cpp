#include "passes/heuristic.h"

#include <tbb/combinable.h>

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "pipeline/frame_context.h"

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

std::vector<ObjectHeuristic> evaluateObjects(const Scene& scene, const std::vector<Bounds3>& bounds,
                                             const Camera& cam, const std::vector<uint32_t>& pixels,
                                             const std::vector<uint8_t>& selectedLast, double I) {
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
    h.Q = lights;
    if (m.reflectivity > 0) h.Q += lights + 1;
    if (m.opacity < 1) h.Q += lights + 4;
    h.S = o < selectedLast.size() && selectedLast[o];
    h.C = h.A * h.Q * hp.E;                // eq. 2
    h.R = ((h.S ? I : 0.0) + h.V) * hp.K;  // eq. 3
    out.push_back(h);
  }
  return out;
}

std::vector<ParamDesc> HeuristicPass::params() const {
  return {
      {"budget",
       ParamType::Float,
       2e6,
       0,
       1e15,
       "T: ray-tracing budget in cost units (visible pixels x rays x E)",
       {}},
      {"importance",
       ParamType::Float,
       1000,
       0,
       1e12,
       "I: relevancy bonus for objects selected last frame (stability)",
       {}},
      {"select_all", ParamType::Bool, 0, 0, 1, "select every visible object (no heuristic)", {}}};
}

void HeuristicPass::execute(FrameContext& ctx) {
  const Scene& scene = *ctx.scene;
  const size_t n = scene.objects.size();
  if (boundsVersion_ != ctx.frame.geometryVersion || bounds_.size() != n) {
    bounds_.assign(n, Bounds3{});
    for (size_t o = 0; o < n; ++o)
      for (const Vec3& p : ctx.frame.objects[o].positions) bounds_[o].extend(p);
    boundsVersion_ = ctx.frame.geometryVersion;
  }
  const Buffer& ids = ctx.input(bufferName("object_id"));
  std::vector<uint32_t> pixels = countObjectPixels(ids, n);
  selectedLast_.resize(n, 0);
  evaluated_ =
      evaluateObjects(scene, bounds_, ctx.camera, pixels, selectedLast_, param("importance"));
  std::vector<uint8_t> selected(n, 0);
  if (param("select_all") != 0) {
    selected_.clear();
    for (const ObjectHeuristic& h : evaluated_) selected_.push_back(h.object);
  } else {
    std::vector<HeuristicNode> nodes;
    for (const ObjectHeuristic& h : evaluated_) nodes.push_back({h.object, h.C, h.R});
    selected_ = selectWithinBudget(std::move(nodes), param("budget"));
  }
  for (int o : selected_) selected[size_t(o)] = 1;
  selectedLast_ = selected;
  Buffer& mask = ctx.output(bufferName("heuristic_mask"), 1);
  parallelRange(
      mask.pixelCount(),
      [&](size_t b, size_t e) {
        for (size_t i = b; i < e; ++i) {
          float id = ids.data[i];
          mask.data[i] = id >= 0 && selected[size_t(id)] ? 1.0f : 0.0f;
        }
      },
      1 << 14);
}

}  // namespace tandem
