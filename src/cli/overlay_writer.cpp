#include "cli/overlay_writer.hpp"

#include <cctype>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <numbers>

namespace depthtrack::cli {

namespace {
std::string format(const char* pattern, double a, double b = 0, double c = 0) {
  char text[128];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}
}  // namespace

std::vector<std::string> overlay_text(const TrackedFrame& f, int particles) {
  std::vector<std::string> lines = {"FRAME " + f.name + format("  T %.3f S", f.timestamp)};
  if (f.ground_truth)
    lines.push_back(format("ERR %.1f MM %.2f DEG  ADD-S %.1f MM", 1000 * f.translation_error,
                           f.rotation_error * 180.0 / std::numbers::pi, 1000 * f.adds));
  lines.push_back(format("ESS %.1f OF %.0f", f.estimate.effective_sample_size, particles));
  std::string status = to_string(f.estimate.status);
  for (char& c : status) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  lines.push_back(status + format("  CONFIDENCE %.2f", f.estimate.confidence));
  return lines;
}

std::vector<std::filesystem::path> stage_overlay(const std::filesystem::path& dir, const Sequence& sequence,
                                                 StagedOutputs& outputs) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error || !std::filesystem::is_directory(dir))
    throw InputError("--overlay: cannot create the folder '" + dir.string() + "'" +
                     (error ? ": " + error.message() : ""));
  std::vector<std::filesystem::path> files;
  for (const SequenceFrame& f : sequence.frames) files.push_back(outputs.add("--overlay", dir / (f.name + ".png")));
  return files;
}

std::vector<std::string> overlay_text(const std::vector<const TrackedFrame*>& frames,
                                      const std::vector<std::string>& names, int particles) {
  if (frames.size() == 1) return overlay_text(*frames.front(), particles);
  std::vector<std::string> lines = {"FRAME " + frames.front()->name + format("  T %.3f S", frames.front()->timestamp)};
  for (size_t j = 0; j < frames.size(); ++j) {
    const TrackedFrame& f = *frames[j];
    std::string status = to_string(f.estimate.status);
    if (f.ground_truth)
      lines.push_back(names[j] + format("  ERR %.1f MM %.2f DEG  ADD-S %.1f MM", 1000 * f.translation_error,
                                        f.rotation_error * 180.0 / std::numbers::pi, 1000 * f.adds));
    lines.push_back(names[j] + "  " + status +
                    format("  CONFIDENCE %.2f  ESS %.1f OF %.0f", f.estimate.confidence,
                           f.estimate.effective_sample_size, particles));
  }
  for (std::string& line : lines)
    for (char& c : line) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return lines;
}

OverlayWriter::OverlayWriter(std::vector<std::filesystem::path> files, const std::vector<const Mesh*>& meshes,
                             const Sequence& sequence)
    : files_(std::move(files)), sequence_(sequence) {
  for (const Mesh* mesh : meshes) painters_.emplace_back(*mesh, sequence.camera);
}

void OverlayWriter::write(size_t i, const std::vector<const TrackedFrame*>& frames,
                          const std::vector<std::string>& names, int particles) const {
  const SequenceFrame& f = sequence_.frames.at(i);
  viz::RgbImage image = f.colour_path.empty() ? viz::colour_mapped_depth(sequence_.load_depth(i))
                                              : viz::RgbImage::load_png(f.colour_path);
  // Each object's marks over the last's picture; the text once, on top.
  for (size_t j = 0; j < painters_.size(); ++j)
    image = painters_[j].paint(
        image, frames.at(j)->estimate.pose,
        j + 1 == painters_.size() ? overlay_text(frames, names, particles) : std::vector<std::string>{});
  image.save_png(files_.at(i));
}

}  // namespace depthtrack::cli
