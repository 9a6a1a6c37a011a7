// Scores one tracker's CSV (what `depthtrack track` or depthtrack_pcl_tracking writes) against the
// sequence's ground truth, the same way for every tracker, and prints one Markdown table row:
// | label | tracker | mean translation mm | max mm | mean rotation deg | last-frame ADD-S mm | ms/frame |
// Columns are found by header name (tx..qz, frame), so columns added later do not matter.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <sstream>

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

}  // namespace

int main(int argc, char** argv) {
  std::string mesh_path, sequence_path, object, csv, label, tracker, ms = "n/a";
  CLI::App app("Score a tracking CSV against a sequence's ground truth; prints one Markdown table row");
  app.add_option("--mesh", mesh_path, "Object mesh (for ADD-S)")->required();
  app.add_option("--sequence", sequence_path, "Sequence folder with ground truth")->required();
  app.add_option("--object", object, "Object of a multi-object clip");
  app.add_option("--csv", csv, "Tracking CSV (frame,...,tx,ty,tz,qw,qx,qy,qz,...)")->required();
  app.add_option("--label", label, "First column: sequence / object")->required();
  app.add_option("--tracker", tracker, "Second column: tracker and settings")->required();
  app.add_option("--ms-per-frame", ms, "Last column, as measured by the caller");
  try {
    app.parse(argc, argv);
    const Mesh mesh = Mesh::load(mesh_path);
    const Sequence seq = load_sequence(sequence_path, object);
    const auto poses = read_poses(csv);
    const AddsMetric adds(mesh);
    double sum_t = 0, sum_r = 0, max_t = 0, last_adds = NAN;
    size_t n = 0;
    for (const SequenceFrame& f : seq.frames) {
      if (!f.ground_truth) throw InputError("'" + sequence_path + "' frame " + f.name + " has no ground truth");
      const auto it = poses.find(f.name);
      if (it == poses.end()) throw InputError("'" + csv + "' has no row for frame " + f.name);
      const double t = translation_error(it->second, *f.ground_truth);
      sum_t += t;
      max_t = std::max(max_t, t);
      sum_r += rotation_error(it->second, *f.ground_truth);
      last_adds = adds(it->second, *f.ground_truth);
      ++n;
    }
    if (n == 0) throw InputError("'" + sequence_path + "' has no frames");
    const double frames = static_cast<double>(n);
    std::printf("| %s | %s | %.2f | %.2f | %.2f | %.2f | %s |\n", label.c_str(), tracker.c_str(), 1000 * sum_t / frames,
                1000 * max_t, sum_r / frames * 180.0 / std::numbers::pi, 1000 * last_adds, ms.c_str());
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "peer_score: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
