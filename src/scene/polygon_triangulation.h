// Triangulation of a file's polygons (OBJ faces of any size) in bounded time. A convex polygon
// (the common case: quads, n-gons of caps) is a fan, O(n). A non-convex one is ear-clipped,
// O(n^3) in the worst case, up to kMaxEarClipVertices vertices; beyond that it is a fan too (a
// huge non-convex face is rare and a fan keeps every vertex: the load stays fast instead of
// taking minutes, as tinyobjloader's own triangulation did on a 100k-vertex face).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/math.h"

namespace tandem {

constexpr size_t kMaxEarClipVertices = 256;

// Triangles (indices into `polygon`, same winding as the polygon) covering the polygon; n - 2 of
// them for n >= 3 vertices, none for fewer.
std::vector<std::array<uint32_t, 3>> triangulatePolygon(const std::vector<Vec3>& polygon);

}  // namespace tandem
