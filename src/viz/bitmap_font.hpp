#pragma once
// A built-in 5x7 pixel font (upper case, digits, common punctuation) for the text of track's overlay
// pictures, so they need no font library. Lower case is drawn as upper case; other characters as '?'.
#include <string>

#include "viz/rgb_image.hpp"

namespace depthtrack::viz {

inline constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphAdvance = 6;  // advance: one column of spacing

// Draws text with its top-left corner at (x, y), each font pixel scale x scale image pixels.
void draw_text(RgbImage& image, int x, int y, const std::string& text, Rgb colour, int scale = 1);
// Width and height in image pixels that draw_text covers.
int text_width(const std::string& text, int scale = 1);
inline int text_height(int scale = 1) {
  return kGlyphHeight * scale;
}

}  // namespace depthtrack::viz
