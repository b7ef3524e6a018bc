// A 5 x 7 pixel font for labelling images (contact sheets, figures) without a font file:
// upper-case letters (lower case is drawn upper case), digits and common punctuation ('*' is a
// multiplication sign); any other character is drawn as a box.
#pragma once
#include <string>

#include "core/buffer.h"
#include "core/math.h"

namespace tandem {

constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphAdvance = 6;

// Draws `text` with its top-left corner at (x, y), each font pixel `scale` x `scale` image
// pixels, in `color` (first three channels of a display-space image); clipped to the image.
void drawText(Buffer& img, int x, int y, const std::string& text, Vec3 color, int scale = 1);
// Width in image pixels of `text` drawn at `scale`.
int textWidth(const std::string& text, int scale = 1);

}  // namespace tandem
