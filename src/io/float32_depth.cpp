// Raw little-endian float32 depth (a ROS 32FC1 image dumped to a file).
#include <bit>
#include <cstdint>
#include <cstring>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/error.hpp>
#include <fstream>
#include <system_error>

namespace depthtrack {

DepthImage DepthImage::load_float32(const std::filesystem::path& path, int width, int height) {
  if (width <= 0 || height <= 0)
    throw InputError("float32 depth file '" + path.string() + "': image size " + std::to_string(width) + "x" +
                     std::to_string(height) + " is invalid");
  std::error_code error;
  const auto bytes = std::filesystem::file_size(path, error);
  if (error) throw InputError("cannot open float32 depth file '" + path.string() + "': " + error.message());
  const uint64_t expected = static_cast<uint64_t>(width) * static_cast<uint64_t>(height) * sizeof(float);
  // The file carries no header, so its exact size is the only check that width and height are right.
  if (bytes != expected)
    throw InputError("float32 depth file '" + path.string() + "' has " + std::to_string(bytes) + " bytes but a " +
                     std::to_string(width) + "x" + std::to_string(height) + " image needs " + std::to_string(expected));
  std::ifstream in(path, std::ios::binary);
  std::vector<uint32_t> raw(static_cast<size_t>(width) * static_cast<size_t>(height));
  if (!in || !in.read(reinterpret_cast<char*>(raw.data()), static_cast<std::streamsize>(expected)))
    throw InputError("cannot read float32 depth file '" + path.string() + "'");
  std::vector<float> metres(raw.size());
  for (size_t i = 0; i < raw.size(); ++i) {
    uint32_t bits = raw[i];
    if constexpr (std::endian::native == std::endian::big)
      bits = (bits >> 24) | ((bits >> 8) & 0xff00u) | ((bits << 8) & 0xff0000u) | (bits << 24);
    metres[i] = std::bit_cast<float>(bits);
  }
  try {
    return from_metres(width, height, std::move(metres));
  } catch (const InputError& e) {
    throw InputError("float32 depth file '" + path.string() + "': " + e.what());
  }
}

}  // namespace depthtrack
