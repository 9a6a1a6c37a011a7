// Picks the sequence reader from the files present, and loads a frame's depth.
#include <cmath>
#include <depthtrack/error.hpp>
#include <string>

#include "core/timestamp_limits.hpp"
#include "io/png_depth.hpp"
#include "io/sequence_formats.hpp"
#include "io/visp_simulated_sequence.hpp"

namespace depthtrack {

namespace {

Sequence checked_times(Sequence sequence, const std::filesystem::path& dir) {
  const auto fail = [&](size_t i, const std::string& problem) {
    throw InputError("sequence '" + dir.string() + "': frame '" + sequence.frames[i].name + "' " + problem);
  };
  for (size_t i = 0; i < sequence.frames.size(); ++i) {
    const double t = sequence.frames[i].timestamp;
    if (!std::isfinite(t) || std::abs(t) >= kMaxAbsTimestamp)
      fail(i, "has timestamp " + std::to_string(t) + " s, outside the sane range (-1e10, 1e10) s");
    if (i == 0) continue;
    const double step = t - sequence.frames[i - 1].timestamp;
    if (step > kMaxTimeStep)
      fail(i, "comes " + std::to_string(step) + " s after the previous frame, more than a day (" +
                  std::to_string(kMaxTimeStep) + " s): a corrupt timestamp or frame id?");
  }
  return sequence;
}

Sequence load_any(const std::filesystem::path& dir, const std::string& object) {
  std::error_code error;
  if (!std::filesystem::exists(dir, error)) throw InputError("sequence folder '" + dir.string() + "' does not exist");
  if (!std::filesystem::is_directory(dir, error))
    throw InputError("sequence folder '" + dir.string() + "' is not a folder");
  if (std::filesystem::exists(dir / io::kDepthtrackManifest, error)) return io::load_depthtrack_sequence(dir, object);
  if (std::filesystem::exists(dir / io::kYcbVideoManifest, error)) return io::load_ycb_video_sequence(dir, object);
  if (std::filesystem::exists(dir / io::kBopManifest, error)) return io::load_bop_sequence(dir, object);
  if (io::is_visp_simulated_folder(dir)) return io::load_visp_simulated_sequence(dir, io::castle_options());
  throw InputError("sequence folder '" + dir.string() + "' has none of " + io::kDepthtrackManifest + " (depthtrack), " +
                   io::kYcbVideoManifest + " (YCB-Video), " + io::kBopManifest +
                   " (BOP) and Depth/ + CameraPose/ + Config/ (ViSP simulated)");
}

}  // namespace

Sequence load_sequence(const std::filesystem::path& dir, const std::string& object) {
  return checked_times(load_any(dir, object), dir);
}

DepthImage Sequence::load_depth(size_t i) const {
  if (i >= frames.size())
    throw InputError("frame index " + std::to_string(i) + " is out of range: the sequence has " +
                     std::to_string(frames.size()) + " frames");
  const auto& path = frames[i].depth_path;
  if (format == io::kVispSimulatedFormat)
    return io::read_visp_depth(path, metres_per_unit, camera.width, camera.height);
  if (path.extension() == ".f32") return DepthImage::load_float32(path, camera.width, camera.height);
  // The size is checked from the header, before a wrong (or hostile, 16384x16384) image is decoded.
  return io::load_depth_png(path, metres_per_unit, io::ImageSize{camera.width, camera.height});
}

}  // namespace depthtrack
