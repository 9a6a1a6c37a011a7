#pragma once
// What a whole `track` run achieved: the numbers printed at its end and written by --summary.
#include <depthtrack/evaluation.hpp>
#include <depthtrack/tracker_config.hpp>
#include <filesystem>
#include <string>
#include <vector>

namespace depthtrack::cli {

struct RunStats {
  size_t frames = 0;
  double seconds = 0, frames_per_second = 0, mean_ess = 0;
  bool ground_truth = false;  // every frame had ground truth; the error figures below are then set
  double mean_err_t_mm = 0, max_err_t_mm = 0, mean_err_r_deg = 0, max_err_r_deg = 0, mean_adds_mm = 0, max_adds_mm = 0;
};

RunStats run_stats(const std::vector<TrackedFrame>& frames, double seconds);

// One line of JSON: the stats plus what was run (sequence, mesh, backend, particles, resolution).
std::string summary_json(const RunStats& stats, const TrackerConfig& config, const std::string& sequence,
                         const std::string& mesh);

// Several objects tracked together (track with --mesh/--object pairs): the run's frames, seconds and
// frames per second and what was run, then per object its name, mesh and stats, as one line of JSON.
struct ObjectStats {
  std::string object, mesh;
  RunStats stats;
};
std::string objects_summary_json(const std::vector<ObjectStats>& objects, size_t frames, double seconds,
                                 const TrackerConfig& config, const std::string& sequence);

// Writes text and a newline to path, or to stdout when path is "-".
void write_summary(const std::filesystem::path& path, const std::string& text);

}  // namespace depthtrack::cli
