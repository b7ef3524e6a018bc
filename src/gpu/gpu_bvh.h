// A binary BVH in the GPU's node layout (shaders/bvh.h), built by Embree's SAH builder
// (rtcBuildBVH): the one Tandem already links, so the GPU's trees are as good as the CPU's.
#pragma once
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "gpu/shaders/bvh.h"

namespace tandem {

struct BvhBuild {
  std::vector<BvhNode> nodes;   // nodes[0] is the root; children and items indexed from 0
  std::vector<uint32_t> items;  // the input indices in leaf order (a leaf's a..a+count-1)
};

// A BVH over `boxes` (leaves of at most 4), node and item indices relative to the first;
// children always come after their parent (a refit walks the nodes backwards).
BvhBuild buildBvh(const std::vector<Bounds3>& boxes);

}  // namespace tandem
