// The label font draws inside the box textWidth and the glyph height promise, in the colour
// asked, and distinct characters look distinct.
#include "core/bitmap_font.h"

#include <gtest/gtest.h>

namespace tandem {
namespace {

struct Ink {
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
  size_t pixels = 0;
};

Ink inkOf(const Buffer& img) {
  Ink k;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (img.at(x, y)[0] > 0.5f) {
        k.x0 = std::min(k.x0, x), k.y0 = std::min(k.y0, y);
        k.x1 = std::max(k.x1, x), k.y1 = std::max(k.y1, y);
        ++k.pixels;
      }
  return k;
}

TEST(BitmapFont, DrawsWithinItsBoxAtAnyScale) {
  for (int scale : {1, 2, 3}) {
    Buffer img(200, 40, 3, 0.0f);
    const std::string text = "HYBRID-DOF 12.5 MS";
    drawText(img, 10, 5, text, Vec3(1, 0.25f, 0), scale);
    const Ink k = inkOf(img);
    ASSERT_GT(k.pixels, 0u);
    EXPECT_GE(k.x0, 10);
    EXPECT_GE(k.y0, 5);
    EXPECT_LT(k.x1, std::min(200, 10 + textWidth(text, scale)));
    EXPECT_LT(k.y1, 5 + kGlyphHeight * scale);
    for (size_t i = 0; i < img.pixelCount(); ++i) {  // ink in the colour asked, or untouched
      if (img.data[3 * i] > 0.5f) {
        EXPECT_EQ(img.data[3 * i + 1], 0.25f);
      }
    }
  }
}

TEST(BitmapFont, CharactersAreDistinctAndLowerCaseIsUpperCase) {
  auto render = [](const std::string& s) {
    Buffer img(8, 8, 1, 0.0f);
    drawText(img, 1, 0, s, Vec3(1.0f));
    return img.data;
  };
  const std::string chars = "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-+.,:()/%=*";
  for (size_t i = 0; i < chars.size(); ++i)
    for (size_t j = i + 1; j < chars.size(); ++j)
      EXPECT_NE(render(chars.substr(i, 1)), render(chars.substr(j, 1)))
          << chars[i] << " and " << chars[j];
  EXPECT_EQ(render("a"), render("A"));
  EXPECT_EQ(render(" "), std::vector<float>(64, 0.0f));
  // Off the image: clipped, no crash.
  Buffer img(4, 4, 3, 0.0f);
  drawText(img, -20, -3, "CLIPPED TEXT", Vec3(1.0f), 3);
  EXPECT_EQ(textWidth("", 2), 0);
}

}  // namespace
}  // namespace tandem
