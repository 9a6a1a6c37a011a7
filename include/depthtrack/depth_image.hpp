#pragma once
/// @file
/// A depth image in float metres; a pixel without a measurement holds NaN.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace depthtrack {

/// A depth image in float metres, row-major; a pixel without a measurement holds NaN.
class DepthImage {
 public:
  /// An empty image (0 x 0).
  DepthImage() = default;
  /// All pixels invalid (NaN).
  DepthImage(int width, int height);

  /// From float metres: NaN, +inf and 0 mean "no measurement" (sensor conventions); a negative
  /// value or -inf is rejected with an InputError naming the pixel. Size must be width*height.
  static DepthImage from_metres(int width, int height, std::vector<float> metres);
  /// From 16-bit sensor units: metres = value * metres_per_unit, 0 = no measurement.
  static DepthImage from_units(int width, int height, const std::vector<uint16_t>& units, double metres_per_unit);

  /// 16-bit greyscale PNG (0 = missing). metres_per_unit: 0.001 for millimetres, 1/10000 for YCB-Video.
  static DepthImage load_png(const std::filesystem::path& path, double metres_per_unit);
  /// Raw little-endian float32, row-major, width*height values, NaN = missing (ROS 32FC1 dumped).
  static DepthImage load_float32(const std::filesystem::path& path, int width, int height);
  /// Writes a 16-bit greyscale PNG; values beyond the 16-bit range are an error, NaN is written as 0.
  void save_png(const std::filesystem::path& path, double metres_per_unit) const;

  int width() const { return width_; }    ///< pixels
  int height() const { return height_; }  ///< pixels
  /// The depth (metres, NaN = missing) of pixel column u, row v; unchecked: u < width(), v < height().
  float at(int u, int v) const { return data_[static_cast<size_t>(v) * width_ + u]; }
  /// The depth of pixel (u, v) to write; unchecked as at() const.
  float& at(int u, int v) { return data_[static_cast<size_t>(v) * width_ + u]; }
  /// Whether z is a measurement: finite and positive.
  static bool is_valid(float z) { return std::isfinite(z) && z > 0.0f; }
  /// Every pixel, row-major (width() * height() values).
  const std::vector<float>& data() const { return data_; }
  /// The pixels holding a measurement (is_valid).
  size_t valid_count() const;

  /// Keeps every factor-th pixel starting at (0, 0), matching Camera::decimated.
  DepthImage decimated(int factor) const;

 private:
  int width_ = 0, height_ = 0;
  std::vector<float> data_;
};

}  // namespace depthtrack
