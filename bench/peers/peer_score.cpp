// Scores a tracker's CSVs (what `depthtrack track` or depthtrack_pcl_tracking writes) against the
// sequence's ground truth, the same way for every tracker, and prints one Markdown table row:
// | label | tracker | mean translation mm | max mm | mean rotation deg | mean ADD-S mm | last-frame ADD-S mm |
//   ADD-S AUC 0-100 mm | ms/frame |
// The AUC is YCB-Video's: the area under the share of frames whose ADD-S is within a threshold, for
// thresholds from 0 to 100 mm, in percent; integrated exactly (no grid of thresholds) as the mean
// over frames of max(0, 1 - ADD-S / 100 mm).
// Several CSVs (repeated runs: of a tracker whose randomness cannot be seeded, like PCL's, or from
// several seeded starts) give the mean over the runs with the range of the per-run values in brackets.
// Columns are found by header name (tx..qz, frame), so columns added later do not matter.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <sstream>

#include "peer_run.hpp"

using namespace depthtrack;

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(field);
  return fields;
}

// frame name -> estimated pose, from the CSV's frame,tx,ty,tz,qw,qx,qy,qz columns.
std::map<std::string, Pose> read_poses(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot read '" + path + "'");
  std::string line;
  if (!std::getline(in, line)) throw InputError("'" + path + "' is empty");
  const auto header = split(line);
  std::map<std::string, size_t> column;
  for (size_t i = 0; i < header.size(); ++i) column[header[i]] = i;
  for (const char* name : {"frame", "tx", "ty", "tz", "qw", "qx", "qy", "qz"})
    if (!column.count(name)) throw InputError("'" + path + "' has no column '" + name + "'");
  std::map<std::string, Pose> poses;
  for (int row = 2; std::getline(in, line); ++row) {
    const auto f = split(line);
    auto number = [&](const char* name) {
      const size_t i = column[name];
      try {
        if (i < f.size()) return std::stod(f[i]);
      } catch (const std::exception&) {
      }
      throw InputError("'" + path + "' row " + std::to_string(row) + ": column '" + name + "' is not a number");
    };
    poses[f.at(column["frame"])] = Pose({number("tx"), number("ty"), number("tz")},
                                        Eigen::Quaterniond(number("qw"), number("qx"), number("qy"), number("qz")));
  }
  return poses;
}

constexpr double kAucMaxMm = 100;  // the AUC's largest threshold

struct Score {
  double mean_t = 0, max_t = 0, mean_r = 0, mean_adds = 0, last_adds = NAN, adds_auc = 0;  // mm, mm, deg, mm, mm, %
};

Score score(const Sequence& seq, const std::string& sequence_path, const AddsMetric& adds, const std::string& csv) {
  const auto poses = read_poses(csv);
  if (poses.size() != seq.frames.size())
    throw InputError("'" + csv + "' has " + std::to_string(poses.size()) + " frames but '" + sequence_path + "' has " +
                     std::to_string(seq.frames.size()) + ": not a run over this sequence");
  Score s;
  size_t n = 0;
  for (const SequenceFrame& f : seq.frames) {
    if (!f.ground_truth) throw InputError("'" + sequence_path + "' frame " + f.name + " has no ground truth");
    const auto it = poses.find(f.name);
    if (it == poses.end()) throw InputError("'" + csv + "' has no row for frame " + f.name);
    const double t = 1000 * translation_error(it->second, *f.ground_truth);
    s.mean_t += t;
    s.max_t = std::max(s.max_t, t);
    s.mean_r += rotation_error(it->second, *f.ground_truth) * 180.0 / std::numbers::pi;
    s.last_adds = 1000 * adds(it->second, *f.ground_truth);
    s.mean_adds += s.last_adds;
    s.adds_auc += 100 * std::max(0.0, 1 - s.last_adds / kAucMaxMm);
    ++n;
  }
  if (n == 0) throw InputError("'" + sequence_path + "' has no frames");
  s.mean_t /= static_cast<double>(n);
  s.mean_r /= static_cast<double>(n);
  s.mean_adds /= static_cast<double>(n);
  s.adds_auc /= static_cast<double>(n);
  return s;
}

// "2.31" for one run, "2.31 (1.98-2.70)" for several.
std::string summary(const std::vector<Score>& runs, double Score::*field) {
  double sum = 0, lo = INFINITY, hi = -INFINITY;
  for (const Score& s : runs) {
    sum += s.*field;
    lo = std::min(lo, s.*field);
    hi = std::max(hi, s.*field);
  }
  char text[64];
  if (runs.size() == 1)
    std::snprintf(text, sizeof text, "%.2f", sum);
  else
    std::snprintf(text, sizeof text, "%.2f (%.2f-%.2f)", sum / static_cast<double>(runs.size()), lo, hi);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  std::string mesh_path, sequence_path, object, label, tracker, ms = "n/a";
  std::vector<std::string> csvs;
  CLI::App app("Score tracking CSVs against a sequence's ground truth; prints one Markdown table row");
  app.add_option("--mesh", mesh_path, "Object mesh (for ADD-S)")->required();
  app.add_option("--sequence", sequence_path, "Sequence folder with ground truth")->required();
  app.add_option("--object", object, "Object of a multi-object clip");
  app.add_option("--csv", csvs, "Tracking CSV(s) (frame,...,tx,ty,tz,qw,qx,qy,qz,...); several: repeated runs")
      ->required();
  app.add_option("--label", label, "First column: sequence / object")->required();
  app.add_option("--tracker", tracker, "Second column: tracker and settings")->required();
  app.add_option("--ms-per-frame", ms, "Last column, as measured by the caller");
  return peers::run_peer_program(app, argc, argv, "peer_score", [&] {
    const Mesh mesh = Mesh::load(mesh_path);
    const Sequence seq = load_sequence(sequence_path, object);
    const AddsMetric adds(mesh);
    std::vector<Score> runs;
    for (const auto& csv : csvs) runs.push_back(score(seq, sequence_path, adds, csv));
    std::printf("| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", label.c_str(), tracker.c_str(),
                summary(runs, &Score::mean_t).c_str(), summary(runs, &Score::max_t).c_str(),
                summary(runs, &Score::mean_r).c_str(), summary(runs, &Score::mean_adds).c_str(),
                summary(runs, &Score::last_adds).c_str(), summary(runs, &Score::adds_auc).c_str(), ms.c_str());
  });
}
