#pragma once
// An 8-bit RGB picture: what overlays and plots are drawn into and saved as PNG.
#include <cstdint>
#include <filesystem>
#include <vector>

namespace depthtrack::viz {

struct Rgb {
  uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb&) const = default;
};

class RgbImage {
 public:
  RgbImage() = default;
  RgbImage(int width, int height, Rgb fill = {});

  // Any PNG (grey, palette, RGB, with alpha, 8 or 16 bits) converted to 8-bit RGB; InputError
  // naming the file when it cannot be read.
  static RgbImage load_png(const std::filesystem::path& path);
  void save_png(const std::filesystem::path& path) const;

  int width() const { return width_; }
  int height() const { return height_; }
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }
  Rgb at(int x, int y) const { return pixels_[index(x, y)]; }
  // Pixels outside the image are ignored, so drawing code need not clip.
  void set(int x, int y, Rgb colour);
  // colour over the pixel with the given opacity (0..1).
  void blend(int x, int y, Rgb colour, double opacity);
  void fill_rect(int x0, int y0, int x1, int y1, Rgb colour, double opacity = 1.0);  // [x0, x1) x [y0, y1)
  // A line of the given thickness from (x0, y0) to (x1, y1), both ends included.
  void line(double x0, double y0, double x1, double y1, Rgb colour, int thickness = 1);

 private:
  size_t index(int x, int y) const {
    return static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x);
  }
  int width_ = 0, height_ = 0;
  std::vector<Rgb> pixels_;
};

}  // namespace depthtrack::viz
