// Turning any named buffer into a viewable image (PNG) or a raw one (EXR): depth normalised,
// normals as colour, ids false-coloured, motion vectors as colour, HDR colour tonemapped.
#pragma once
#include <string>

#include "core/buffer.h"

namespace tandem {

// Display-ready RGB in [0,1] (sRGB encoded) for a buffer named `name`. `scale` multiplies the
// standard error shown for `variance`.
Buffer visualizeBuffer(const std::string& name, const Buffer& b, float scale = 1.0f);
// Deterministic distinct colour for an integer id (-1 -> black).
Vec3 idColor(int id);
// Writes a buffer to `path`: EXR gets raw values, PNG the visualisation (or `name == "output"`,
// which is already display encoded).
void writeBuffer(const std::string& path, const std::string& name, const Buffer& b);

}  // namespace tandem
