#pragma once
// The bounding box of one object's pixels in a YCB-Video label image (8-bit PNG, id per pixel):
// the 2D box a detector would hand the tracker.
#include <png.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <vector>

namespace depthtrack::test {

// {u0, v0, u1, v1}, inclusive; nullopt when no pixel carries id.
inline std::optional<std::array<int, 4>> label_box(const std::filesystem::path& path, int id) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) throw std::runtime_error("cannot read " + path.string());
  image.format = PNG_FORMAT_GRAY;
  std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr))
    throw std::runtime_error("cannot decode " + path.string());
  const int w = static_cast<int>(image.width), h = static_cast<int>(image.height);
  std::array<int, 4> box{w, h, -1, -1};
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)
      if (pixels[static_cast<size_t>(v) * static_cast<size_t>(w) + static_cast<size_t>(u)] == id) {
        box = {std::min(box[0], u), std::min(box[1], v), std::max(box[2], u), std::max(box[3], v)};
      }
  if (box[2] < 0) return std::nullopt;
  return box;
}

}  // namespace depthtrack::test
