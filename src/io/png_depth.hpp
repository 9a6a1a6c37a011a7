#pragma once
// Internal to the I/O layer: what other readers need from the PNG code.
#include <depthtrack/depth_image.hpp>
#include <filesystem>
#include <optional>

namespace depthtrack::io {

struct ImageSize {
  int width = 0, height = 0;
};

// Reads only the header of a 16-bit greyscale depth PNG (checked like DepthImage::load_png).
ImageSize read_depth_png_size(const std::filesystem::path& path);
// DepthImage::load_png, refusing an image whose header is not camera_size before any pixel is decoded
// (one open of the file: a wrong or hostile 16384x16384 header costs nothing).
DepthImage load_depth_png(const std::filesystem::path& path, double metres_per_unit,
                          const std::optional<ImageSize>& camera_size);

}  // namespace depthtrack::io
