#pragma once
// Internal to the I/O layer: what other readers need from the PNG code.
#include <filesystem>

namespace depthtrack::io {

struct ImageSize {
  int width = 0, height = 0;
};

// Reads only the header of a 16-bit greyscale depth PNG (checked like DepthImage::load_png).
ImageSize read_depth_png_size(const std::filesystem::path& path);

}  // namespace depthtrack::io
