// DepthImage construction from the two sensor conventions, and the in-memory operations.
#include <algorithm>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/error.hpp>
#include <limits>
#include <sstream>

#include "io/depth_pixel.hpp"

namespace depthtrack {

namespace {

std::string size_text(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

void check_size(int width, int height) {
  // The pixel count must also fit in int: Camera::pixel_count() and the backends use int.
  if (width <= 0 || height <= 0 || width > std::numeric_limits<int>::max() / height)
    throw InputError("depth image size " + size_text(width, height) + " is invalid (both must be positive)");
}

void check_count(int width, int height, size_t count) {
  const size_t expected = static_cast<size_t>(width) * static_cast<size_t>(height);
  if (count != expected)
    throw InputError("depth image of " + size_text(width, height) + " needs " + std::to_string(expected) +
                     " values but got " + std::to_string(count));
}

}  // namespace

DepthImage::DepthImage(int width, int height) : width_(width), height_(height) {
  check_size(width, height);
  data_.assign(static_cast<size_t>(width) * static_cast<size_t>(height), std::numeric_limits<float>::quiet_NaN());
}

DepthImage DepthImage::from_metres(int width, int height, std::vector<float> metres) {
  check_size(width, height);
  check_count(width, height, metres.size());
  const size_t w = static_cast<size_t>(width);
  for (size_t i = 0; i < metres.size(); ++i) metres[i] = io::metres_pixel(metres[i], i % w, i / w);
  DepthImage image;
  image.width_ = width;
  image.height_ = height;
  image.data_ = std::move(metres);
  return image;
}

DepthImage DepthImage::from_units(int width, int height, const std::vector<uint16_t>& units, double metres_per_unit) {
  if (!std::isfinite(metres_per_unit) || metres_per_unit <= 0)
    throw InputError("depth scale metres_per_unit must be finite and positive, got " + std::to_string(metres_per_unit));
  DepthImage image(width, height);
  check_count(width, height, units.size());
  for (size_t i = 0; i < units.size(); ++i) image.data_[i] = io::units_pixel(units[i], metres_per_unit);
  return image;
}

size_t DepthImage::valid_count() const {
  return static_cast<size_t>(std::count_if(data_.begin(), data_.end(), [](float z) { return is_valid(z); }));
}

DepthImage DepthImage::decimated(int factor) const {
  if (factor < 1 || width_ % factor != 0 || height_ % factor != 0)
    throw InputError("cannot decimate a " + size_text(width_, height_) + " depth image by " + std::to_string(factor) +
                     ": the factor must be positive and divide both width and height");
  DepthImage out(width_ / factor, height_ / factor);
  for (int v = 0; v < out.height_; ++v)
    for (int u = 0; u < out.width_; ++u) out.at(u, v) = at(factor * u, factor * v);
  return out;
}

}  // namespace depthtrack
