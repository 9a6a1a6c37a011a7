#pragma once
/// @file
/// A caller's depth image in place (a camera driver's buffer, a numpy array, a ROS message), read by
/// the tracker without a copy on the caller's side: float32 metres (NaN, 0 or +inf = missing) or
/// uint16 sensor units times metres_per_unit (0 = missing), rows row_stride bytes apart.
#include <cstddef>
#include <cstdint>
#include <depthtrack/depth_image.hpp>
#include <limits>

namespace depthtrack {

/// How a DepthView's pixels are stored.
enum class DepthEncoding {
  Float32Metres,  ///< float per pixel, metres
  Uint16Units,    ///< uint16_t per pixel, metres = value * metres_per_unit
};
const char* to_string(DepthEncoding encoding);  ///< "float32 metres", "uint16 units"

/// A caller's depth buffer in place (see the file's notes); it must live while the call that reads it runs.
struct DepthView {
  const void* data = nullptr;  ///< the first pixel of the first row; read only, never kept
  int width = 0, height = 0;   ///< pixels
  size_t row_stride = 0;       ///< bytes from one row's first pixel to the next's (at least width * element size)
  DepthEncoding encoding = DepthEncoding::Float32Metres;
  double metres_per_unit = 0;  ///< Uint16Units only

  /// A view of float32 metres; row_stride_bytes 0: rows packed one after the other.
  static DepthView metres(const float* data, int width, int height, size_t row_stride_bytes = 0);
  /// A view of uint16 sensor units (metres = value * metres_per_unit); row_stride_bytes as metres().
  static DepthView units(const uint16_t* data, int width, int height, double metres_per_unit,
                         size_t row_stride_bytes = 0);

  /// Bytes per pixel: 4 (float32) or 2 (uint16).
  size_t element_size() const;
  /// InputError naming the problem: null data, a non-positive size, a stride shorter than a row, or
  /// (uint16) a metres_per_unit that is not finite and positive.
  void validate() const;
  /// Every pixel checked as DepthImage::from_metres / from_units do (a negative float is an
  /// InputError naming the pixel), every factor-th pixel of every factor-th row kept (as
  /// DepthImage::decimated), and depths beyond max_depth made missing: one pass over the view.
  DepthImage sample(int factor = 1, float max_depth = std::numeric_limits<float>::infinity()) const;
  /// The whole image as a DepthImage (factor 1, nothing dropped).
  DepthImage to_image() const { return sample(); }
};

}  // namespace depthtrack
