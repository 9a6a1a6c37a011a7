// write_synthetic_sequence: the Synthesizer's frames on disk in depthtrack's own sequence layout.
#include <algorithm>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <depthtrack/synth.hpp>
#include <sstream>
#include <string>
#include <system_error>

namespace depthtrack {

namespace {
std::string frame_name(int index) {
  char name[16];
  std::snprintf(name, sizeof name, "%06d", index);
  return name;
}

// Fails before any file is written when the PNG scale cannot hold the deepest possible reading.
void check_png_range(const SynthConfig& config) {
  // Noise and quantization can push a reading a little beyond max_depth: leave a quarter's headroom.
  const double deepest = 1.25 * std::max(config.sensor.max_depth, config.background_depth);
  if (deepest / config.metres_per_unit > 65535.0) {
    std::ostringstream message;
    message << "synthetic sequence: metres_per_unit = " << config.metres_per_unit << " cannot store depths up to "
            << deepest << " m in 16-bit PNGs";
    throw InputError(message.str());
  }
}
}  // namespace

Sequence write_synthetic_sequence(const std::filesystem::path& dir, const Mesh& mesh, const SynthConfig& config,
                                  const std::function<void(int, const SynthFrame&)>& on_frame) {
  const Synthesizer synthesizer(mesh, config);  // validates before touching the disk
  check_png_range(config);
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw InputError("cannot create folder " + dir.string() + ": " + error.message());

  Sequence sequence;
  sequence.format = "depthtrack";
  sequence.camera = config.camera;
  sequence.metres_per_unit = config.metres_per_unit;
  sequence.object = config.object;
  for (int i = 0; i < config.frames; ++i) {
    const SynthFrame frame = synthesizer.frame(i);
    SequenceFrame entry;
    entry.name = frame_name(i);
    entry.timestamp = frame.timestamp;
    entry.depth_path = dir / ("depth_" + entry.name + ".png");
    entry.ground_truth = frame.ground_truth;
    frame.depth.save_png(entry.depth_path, config.metres_per_unit);
    sequence.frames.push_back(std::move(entry));
    if (on_frame) on_frame(i, frame);
  }
  write_sequence_manifest(dir, sequence);
  return sequence;
}

}  // namespace depthtrack
