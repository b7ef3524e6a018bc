// Conservative depth for classified shadows: every texel a caster's triangle touches (not only
// those whose centre it covers) records the nearest depth the triangle can have inside that texel,
// and which object it was. A caster thinner than a texel therefore never vanishes from the map, so
// "nothing nearer in this texel" is a certainty a shadow ray need not check.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "scene/camera.h"
#include "scene/frame_scene.h"

namespace tandem {

struct ConservativeDepth {
  // Depth and object side by side: a lookup costs one cache line.
  struct Texel {
    float depth;      // reversed-Z as the rasterizer's: the largest (nearest) over the texel
    uint32_t object;  // the object of that depth; kNoObject where nothing touched
  };
  int width = 0, height = 0;
  std::vector<Texel> texels;
};

// The 12 triangles of a box's faces (corner k at lo or hi by its bits x, y, z), as a swept object
// is drawn.
std::array<std::array<Vec3, 3>, 12> boxTriangles(const Bounds3& b);

// Draws the objects with non-zero `objects[o]` (null: all) seen by `cam` (its width x height)
// into `out`, over its contents when `keep`, else into a cleared map. Both faces are drawn.
// `sweep`: objects that move while the shutter is open are drawn as their box over the shutter
// (FrameObject::bounds), so every time a sample may see them at is covered.
void drawConservativeDepth(const FrameScene& fs, const Camera& cam,
                           const std::vector<uint8_t>* objects, bool keep, bool sweep,
                           ConservativeDepth& out);

}  // namespace tandem
