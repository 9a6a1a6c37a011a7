// PNG through libpng's simplified API (png_image), which converts any input format to RGB.
#include "viz/rgb_image.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <depthtrack/error.hpp>
#include <string>

namespace depthtrack::viz {

static_assert(sizeof(Rgb) == 3, "Rgb must be packed: the pixel vector is handed to libpng as bytes");

RgbImage::RgbImage(int width, int height, Rgb fill) : width_(width), height_(height) {
  if (width <= 0 || height <= 0)
    throw InputError("an image must have a positive size, not " + std::to_string(width) + "x" + std::to_string(height));
  pixels_.assign(static_cast<size_t>(width) * static_cast<size_t>(height), fill);
}

RgbImage RgbImage::load_png(const std::filesystem::path& path) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str()))
    throw InputError("cannot read colour image '" + path.string() + "': " + image.message);
  image.format = PNG_FORMAT_RGB;
  if (image.width == 0 || image.height == 0 ||
      static_cast<uint64_t>(image.width) * image.height > (uint64_t{1} << 28)) {
    png_image_free(&image);
    throw InputError("colour image '" + path.string() + "' has an implausible size");
  }
  RgbImage out(static_cast<int>(image.width), static_cast<int>(image.height));
  if (!png_image_finish_read(&image, nullptr, out.pixels_.data(), 0, nullptr)) {
    const std::string message = image.message;
    png_image_free(&image);
    throw InputError("colour image '" + path.string() + "' is corrupt or truncated: " + message);
  }
  return out;
}

void RgbImage::save_png(const std::filesystem::path& path) const {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width_);
  image.height = static_cast<png_uint_32>(height_);
  image.format = PNG_FORMAT_RGB;
  if (!png_image_write_to_file(&image, path.c_str(), 0, pixels_.data(), 0, nullptr))
    throw InputError("cannot write image '" + path.string() + "': " + image.message);
}

void RgbImage::set(int x, int y, Rgb colour) {
  if (contains(x, y)) pixels_[index(x, y)] = colour;
}

void RgbImage::blend(int x, int y, Rgb colour, double opacity) {
  if (!contains(x, y)) return;
  Rgb& p = pixels_[index(x, y)];
  auto mix = [opacity](uint8_t below, uint8_t above) {
    return static_cast<uint8_t>(std::lround((1 - opacity) * below + opacity * above));
  };
  p = {mix(p.r, colour.r), mix(p.g, colour.g), mix(p.b, colour.b)};
}

void RgbImage::fill_rect(int x0, int y0, int x1, int y1, Rgb colour, double opacity) {
  for (int y = std::max(0, y0); y < std::min(height_, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(width_, x1); ++x) blend(x, y, colour, opacity);
}

void RgbImage::line(double x0, double y0, double x1, double y1, Rgb colour, int thickness) {
  const double length = std::max(std::abs(x1 - x0), std::abs(y1 - y0));
  const int steps = std::max(1, static_cast<int>(std::ceil(length)));
  const int before = (thickness - 1) / 2, after = thickness / 2;
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    const int x = static_cast<int>(std::lround(x0 + t * (x1 - x0))),
              y = static_cast<int>(std::lround(y0 + t * (y1 - y0)));
    fill_rect(x - before, y - before, x + after + 1, y + after + 1, colour);
  }
}

}  // namespace depthtrack::viz
