// Triangulation of a file's polygons (OBJ faces of any size) in bounded time. A convex polygon
// (the common case: quads, n-gons of caps) is a fan, O(n). A non-convex one is ear-clipped with
// its reflex vertices in a uniform grid, so an ear test looks only at nearby ones: O(n) tests
// for typical polygons, the work capped at 1024 point tests per vertex (past the cap,
// a contrived input's remainder becomes a fan). tinyobjloader's own triangulation took minutes
// on a 100k-vertex face.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/math.h"

namespace tandem {

// Triangles (indices into `polygon`, same winding as the polygon) covering the polygon; n - 2 of
// them for n >= 3 vertices, none for fewer.
std::vector<std::array<uint32_t, 3>> triangulatePolygon(const std::vector<Vec3>& polygon);

}  // namespace tandem
