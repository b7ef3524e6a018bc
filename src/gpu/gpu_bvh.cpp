#include "gpu/gpu_bvh.h"

#include <embree3/rtcore.h>

#include <mutex>
#include <stdexcept>

namespace tandem {

namespace {

constexpr unsigned kMaxLeaf = 4;

// The builder's tree, in Embree's thread-local memory until it is flattened.
struct Node {
  bool leaf = false;
};
struct Inner : Node {
  Node* child[2] = {nullptr, nullptr};
  Bounds3 bounds[2];
  unsigned children = 0;
};
struct Leaf : Node {
  unsigned count = 0;
  uint32_t ids[kMaxLeaf];
};

void* createNode(RTCThreadLocalAllocator alloc, unsigned, void*) {
  return new (rtcThreadLocalAlloc(alloc, sizeof(Inner), 16)) Inner;
}
void setChildren(void* node, void** children, unsigned n, void*) {
  auto* in = static_cast<Inner*>(node);
  in->children = n;
  for (unsigned i = 0; i < n; ++i) in->child[i] = static_cast<Node*>(children[i]);
}
void setBounds(void* node, const RTCBounds** bounds, unsigned n, void*) {
  auto* in = static_cast<Inner*>(node);
  for (unsigned i = 0; i < n; ++i)
    in->bounds[i] = {{bounds[i]->lower_x, bounds[i]->lower_y, bounds[i]->lower_z},
                     {bounds[i]->upper_x, bounds[i]->upper_y, bounds[i]->upper_z}};
}
void* createLeaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t n, void*) {
  auto* l = new (rtcThreadLocalAlloc(alloc, sizeof(Leaf), 16)) Leaf;
  l->leaf = true;
  l->count = unsigned(n);
  for (size_t i = 0; i < n; ++i) l->ids[i] = prims[i].primID;
  return l;
}

RTCDevice builderDevice() {
  static RTCDevice device = rtcNewDevice(nullptr);
  return device;
}

BvhNode makeNode(const Bounds3& b, uint32_t a, uint32_t count) {
  return {b.lo.x, b.lo.y, b.lo.z, a, b.hi.x, b.hi.y, b.hi.z, count};
}

// Writes `n` (whose bounds are `b`) at out.nodes[slot], its children after everything so far.
void flatten(const Node* n, const Bounds3& b, size_t slot, BvhBuild& out) {
  if (n->leaf) {
    const auto* l = static_cast<const Leaf*>(n);
    out.nodes[slot] = makeNode(b, uint32_t(out.items.size()), l->count);
    out.items.insert(out.items.end(), l->ids, l->ids + l->count);
    return;
  }
  const auto* in = static_cast<const Inner*>(n);
  const size_t first = out.nodes.size();
  out.nodes.resize(first + 2);
  out.nodes[slot] = makeNode(b, uint32_t(first), 0);
  flatten(in->child[0], in->bounds[0], first, out);
  if (in->children > 1) {
    flatten(in->child[1], in->bounds[1], first + 1, out);
  } else {  // one child: the second slot an empty leaf whose box nothing enters
    Bounds3 none;
    out.nodes[first + 1] = makeNode(none, 0, 0);
  }
}

}  // namespace

BvhBuild buildBvh(const std::vector<Bounds3>& boxes) {
  BvhBuild out;
  out.nodes.resize(1);
  Bounds3 all;
  for (const Bounds3& b : boxes) all.extend(b);
  if (boxes.empty()) {
    out.nodes[0] = makeNode(Bounds3{}, 0, 0);
    return out;
  }
  std::vector<RTCBuildPrimitive> prims(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) {
    const Bounds3& b = boxes[i];
    prims[i] = {b.lo.x, b.lo.y, b.lo.z, 0, b.hi.x, b.hi.y, b.hi.z, unsigned(i)};
  }
  RTCBVH bvh = rtcNewBVH(builderDevice());
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.byteSize = sizeof(args);
  args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;  // no spatial splits: each item in one leaf
  args.maxBranchingFactor = 2;
  args.maxDepth = 60;  // within the kernels' traversal stacks of 64
  args.minLeafSize = 1;
  args.maxLeafSize = kMaxLeaf;
  args.bvh = bvh;
  args.primitives = prims.data();
  args.primitiveCount = prims.size();
  args.primitiveArrayCapacity = prims.size();
  args.createNode = createNode;
  args.setNodeChildren = setChildren;
  args.setNodeBounds = setBounds;
  args.createLeaf = createLeaf;
  const Node* root = static_cast<const Node*>(rtcBuildBVH(&args));
  if (!root) {
    rtcReleaseBVH(bvh);
    throw std::runtime_error("GPU: the BVH builder failed");
  }
  out.items.reserve(boxes.size());
  flatten(root, all, 0, out);
  rtcReleaseBVH(bvh);  // the builder's nodes live in the BVH object's memory
  return out;
}

}  // namespace tandem
