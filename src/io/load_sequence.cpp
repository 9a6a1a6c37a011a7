// Picks the sequence reader from the files present, and loads a frame's depth.
#include <depthtrack/error.hpp>

#include "io/png_depth.hpp"
#include "io/sequence_formats.hpp"

namespace depthtrack {

Sequence load_sequence(const std::filesystem::path& dir, const std::string& object) {
  std::error_code error;
  if (!std::filesystem::exists(dir, error)) throw InputError("sequence folder '" + dir.string() + "' does not exist");
  if (!std::filesystem::is_directory(dir, error))
    throw InputError("sequence folder '" + dir.string() + "' is not a folder");
  if (std::filesystem::exists(dir / io::kDepthtrackManifest, error)) return io::load_depthtrack_sequence(dir, object);
  if (std::filesystem::exists(dir / io::kYcbVideoManifest, error)) return io::load_ycb_video_sequence(dir, object);
  if (std::filesystem::exists(dir / io::kBopManifest, error)) return io::load_bop_sequence(dir, object);
  throw InputError("sequence folder '" + dir.string() + "' has none of " + io::kDepthtrackManifest + " (depthtrack), " +
                   io::kYcbVideoManifest + " (YCB-Video) and " + io::kBopManifest + " (BOP)");
}

DepthImage Sequence::load_depth(size_t i) const {
  if (i >= frames.size())
    throw InputError("frame index " + std::to_string(i) + " is out of range: the sequence has " +
                     std::to_string(frames.size()) + " frames");
  const auto& path = frames[i].depth_path;
  // The size is checked from the header, before a wrong (or hostile, 16384x16384) image is decoded.
  return io::load_depth_png(path, metres_per_unit, io::ImageSize{camera.width, camera.height});
}

}  // namespace depthtrack
