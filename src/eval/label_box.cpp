#include "eval/label_box.hpp"

#include <png.h>

#include <algorithm>
#include <depthtrack/error.hpp>
#include <string>
#include <vector>

namespace depthtrack {

std::optional<std::array<int, 4>> label_box(const std::filesystem::path& path, int id) {
  if (id < 0 || id > 255) throw InputError("label id " + std::to_string(id) + " is outside an 8-bit label's 0..255");
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str()))
    throw InputError("cannot read the label image '" + path.string() + "': " + image.message);
  image.format = PNG_FORMAT_GRAY;
  std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr))
    throw InputError("cannot decode the label image '" + path.string() + "': " + image.message);
  const int w = static_cast<int>(image.width), h = static_cast<int>(image.height);
  std::array<int, 4> box{w, h, -1, -1};
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u)
      if (pixels[static_cast<size_t>(v) * static_cast<size_t>(w) + static_cast<size_t>(u)] == id)
        box = {std::min(box[0], u), std::min(box[1], v), std::max(box[2], u), std::max(box[3], v)};
  if (box[2] < 0) return std::nullopt;
  return box;
}

std::filesystem::path label_image_beside(const std::filesystem::path& depth) {
  const std::string name = depth.filename().string(), suffix = "-depth.png";
  if (name.size() <= suffix.size() || name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) return {};
  const auto label = depth.parent_path() / (name.substr(0, name.size() - suffix.size()) + "-label.png");
  std::error_code error;
  return std::filesystem::is_regular_file(label, error) ? label : std::filesystem::path();
}

}  // namespace depthtrack
