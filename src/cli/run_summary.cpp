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

namespace {

void add_run(nlohmann::ordered_json& j, const TrackerConfig& config, size_t frames, double seconds,
             double frames_per_second) {
  j["backend"] = config.resolved_backend();
  j["particles"] = config.particles;
  j["resolution"] = std::to_string(config.width) + "x" + std::to_string(config.height);
  j["frames"] = frames;
  j["seconds"] = seconds;
  j["fps"] = frames_per_second;
}

void add_errors(nlohmann::ordered_json& j, const RunStats& s) {
  j["mean_ess"] = s.mean_ess;
  if (s.ground_truth) {
    j["mean_err_t_mm"] = s.mean_err_t_mm;
    j["max_err_t_mm"] = s.max_err_t_mm;
    j["mean_err_r_deg"] = s.mean_err_r_deg;
    j["max_err_r_deg"] = s.max_err_r_deg;
    j["mean_adds_mm"] = s.mean_adds_mm;
    j["max_adds_mm"] = s.max_adds_mm;
  }
}

}  // namespace

std::string summary_json(const RunStats& s, const TrackerConfig& config, const std::string& sequence,
                         const std::string& mesh) {
  nlohmann::ordered_json j;
  j["sequence"] = sequence;
  j["mesh"] = mesh;
  add_run(j, config, s.frames, s.seconds, s.frames_per_second);
  add_errors(j, s);
  return j.dump();
}

std::string objects_summary_json(const std::vector<ObjectStats>& objects, size_t frames, double seconds,
                                 const TrackerConfig& config, const std::string& sequence) {
  nlohmann::ordered_json j;
  j["sequence"] = sequence;
  add_run(j, config, frames, seconds, seconds > 0 ? static_cast<double>(frames) / seconds : 0);
  j["objects"] = nlohmann::ordered_json::array();
  for (const ObjectStats& o : objects) {
    nlohmann::ordered_json one;
    one["object"] = o.object;
    one["mesh"] = o.mesh;
    one["frames"] = o.stats.frames;
    add_errors(one, o.stats);
    j["objects"].push_back(one);
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
