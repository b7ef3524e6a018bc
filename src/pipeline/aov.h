// Turning any buffer into a viewable image (PNG) or a raw one (EXR), by its kind: depth
// normalised, normals as colour, ids false-coloured, motion vectors as colour, HDR colour
// tonemapped, variance as standard error. Reduced-extent buffers keep their own size.
#pragma once
#include <string>
#include <vector>

#include "core/buffer.h"

namespace tandem {

// Display-ready RGB in [0,1] (sRGB encoded), the buffer's size. `scale` multiplies the standard
// error shown for a variance buffer.
Buffer visualizeBuffer(const Buffer& b, float scale = 1.0f);
// Deterministic distinct colour for an integer id (-1 -> black).
Vec3 idColor(int id);
// Writes a buffer to `path`: EXR gets raw values, PNG the visualisation.
void writeBuffer(const std::string& path, const Buffer& b);
// The bytes writeBuffer would write, for staging in a FileCommit. `channels`: the names of a
// buffer's channels for an EXR wider than four (ExrLayer::channels).
std::vector<unsigned char> encodeBuffer(const std::string& path, const Buffer& b,
                                        const std::vector<std::string>& channels = {});

}  // namespace tandem
