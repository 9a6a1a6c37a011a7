#include "cli/run_summary.hpp"

#include <algorithm>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <nlohmann/json.hpp>
#include <numbers>

#include "cli/staged_outputs.hpp"

namespace depthtrack::cli {

RunStats run_stats(const std::vector<TrackedFrame>& frames, double seconds) {
  RunStats s;
  s.frames = frames.size();
  s.seconds = seconds;
  s.frames_per_second = seconds > 0 ? static_cast<double>(frames.size()) / seconds : 0;
  s.ground_truth = !frames.empty() && std::all_of(frames.begin(), frames.end(),
                                                  [](const TrackedFrame& f) { return f.ground_truth.has_value(); });
  if (frames.empty()) return s;
  const double n = static_cast<double>(frames.size()), deg = 180.0 / std::numbers::pi;
  for (const auto& f : frames) {
    s.mean_ess += f.estimate.effective_sample_size / n;
    if (!s.ground_truth) continue;
    s.mean_err_t_mm += 1000 * f.translation_error / n;
    s.max_err_t_mm = std::max(s.max_err_t_mm, 1000 * f.translation_error);
    s.mean_err_r_deg += deg * f.rotation_error / n;
    s.max_err_r_deg = std::max(s.max_err_r_deg, deg * f.rotation_error);
    s.mean_adds_mm += 1000 * f.adds / n;
    s.max_adds_mm = std::max(s.max_adds_mm, 1000 * f.adds);
  }
  return s;
}

std::string summary_json(const RunStats& s, const TrackerConfig& config, const std::string& sequence,
                         const std::string& mesh) {
  nlohmann::ordered_json j;
  j["sequence"] = sequence;
  j["mesh"] = mesh;
  j["backend"] = config.resolved_backend();
  j["particles"] = config.particles;
  j["resolution"] = std::to_string(config.width) + "x" + std::to_string(config.height);
  j["frames"] = s.frames;
  j["seconds"] = s.seconds;
  j["fps"] = s.frames_per_second;
  j["mean_ess"] = s.mean_ess;
  if (s.ground_truth) {
    j["mean_err_t_mm"] = s.mean_err_t_mm;
    j["max_err_t_mm"] = s.max_err_t_mm;
    j["mean_err_r_deg"] = s.mean_err_r_deg;
    j["max_err_r_deg"] = s.max_err_r_deg;
    j["mean_adds_mm"] = s.mean_adds_mm;
    j["max_adds_mm"] = s.max_adds_mm;
  }
  return j.dump();
}

void write_summary(const std::filesystem::path& path, const std::string& text) {
  if (path == "-") {
    std::printf("%s\n", text.c_str());
    return;
  }
  write_text_file(path, text + "\n");
}

}  // namespace depthtrack::cli
