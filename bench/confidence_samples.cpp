// Samples for calibrating the tracker's confidence: on every frame of a clip with ground truth, poses
// right and wrong (the truth, the truth moved by 0.5-150 mm and 0-120 degrees, the object placed on the
// other objects and on the scene's surfaces), each fitted to its likelihood's optimum as the tracker's
// estimates are, then described by the evidence the confidence reads (tracker/silhouette_shares.hpp)
// and scored against the truth. One CSV row per pose; scripts/calibrate-confidence.py fits the model.
//
// With --track the rows are the tracker's own estimates instead, frame by frame: from starts 1 cm / 5 deg
// off the truth (three seeds), from the ground truth's projected box, and from such a start with the
// timestamps jumping by 0.5 s and 2 s before frame 6 (a stalled camera loop).
//
//   depthtrack_confidence_samples --clip DIR --mesh-dir DIR [--object NAME]... [--resolution WxH]
//                                 [--every N] [--seed N] [--track] > samples.csv
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/init_hint.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "core/mesh_simplify.hpp"
#include "model/occlusion_chain.hpp"
#include "reference/pose_refiner.hpp"
#include "reference/rasterizer.hpp"
#include "tracker/confidence_model.hpp"
#include "tracker/silhouette_shares.hpp"

using namespace depthtrack;

namespace {

struct Options {
  std::string clip, mesh_dir;
  std::vector<std::string> objects;  // empty: every object of the clip with a mesh
  std::pair<int, int> size = {80, 60};
  int every = 2;
  uint64_t seed = 1;
  bool track = false;  // rows of tracked frames (perturbed starts, box starts, gaps) instead of sampled poses
};

Options parse(int argc, char** argv) {
  Options o;
  bench::ArgReader args(argc, argv);
  for (std::string option = args.next(); !option.empty(); option = args.next()) {
    if (option == "--clip") {
      o.clip = args.value();
    } else if (option == "--mesh-dir") {
      o.mesh_dir = args.value();
    } else if (option == "--object") {
      o.objects.push_back(args.value());
    } else if (option == "--resolution") {
      o.size = bench::parse_size(args.value(), "--resolution");
    } else if (option == "--every") {
      o.every = std::max(1, std::stoi(args.value()));
    } else if (option == "--track") {
      o.track = true;
    } else if (option == "--seed") {
      o.seed = std::stoull(args.value());
    } else {
      throw InputError("unknown option " + option);
    }
  }
  if (o.clip.empty() || o.mesh_dir.empty()) throw InputError("--clip and --mesh-dir are required");
  return o;
}

// The objects a clip holds: YCB-Video's gt.json names them per frame; an own sequence holds one.
std::vector<std::string> clip_objects(const std::filesystem::path& clip) {
  std::vector<std::string> names;
  const auto gt = clip / "gt.json";
  if (std::filesystem::exists(gt)) {
    std::ifstream in(gt);
    const nlohmann::json j = nlohmann::json::parse(in);
    for (const auto& o : j.at("frames").at(0).at("objects")) names.push_back(o.at("name").get<std::string>());
  } else {
    names.push_back(load_sequence(clip).object);
  }
  return names;
}

std::filesystem::path mesh_path(const std::string& dir, const std::string& name) {
  for (const char* ext : {".obj", ".ply", ".stl", ".off"}) {
    const auto p = std::filesystem::path(dir) / (name + ext);
    if (std::filesystem::exists(p)) return p;
  }
  return {};
}

struct Sample {
  std::string kind;
  Pose pose;
};

void print_row(const std::string& clip, const std::string& object, const std::string& frame, const std::string& kind,
               double start_mm, double start_deg, double adds_m, double diameter, const PoseEvidence& e,
               double confidence, const char* status) {
  std::printf("%s,%s,%s,%s,%.1f,%.1f,%.3f,%.1f,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%s\n", clip.c_str(),
              object.c_str(), frame.c_str(), kind.c_str(), start_mm, start_deg, 1000.0 * adds_m, 1000.0 * diameter,
              e.pixels, e.visible, e.occluded, e.contradicted, e.missing, e.separated, e.outline_nearer, e.visible_rms,
              e.plane_rms, confidence, status);
}

// The tracker's estimates, frame by frame, from the starts a user gives it.
void track_rows(const std::string& clip, const std::string& object, const Sequence& seq, const Mesh& mesh,
                TrackerConfig config, double diameter) {
  config.refine.iterations = Refinement{}.iterations;
  const Pose truth = *seq.frames.at(0).ground_truth;
  const Eigen::Vector3d centre = mesh.centre().cast<double>();
  auto emit = [&](const std::string& kind, const std::vector<TrackedFrame>& frames) {
    for (const TrackedFrame& f : frames)
      print_row(clip, object, f.name, kind, 0, 0, f.adds, diameter, f.estimate.evidence, f.estimate.confidence,
                to_string(f.estimate.status));
    std::fflush(stdout);
  };
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    config.seed = seed;
    emit("track-perturbed",
         track_sequence(seq, mesh, config, perturb_pose(truth, centre, 0.01, 5, seed), {0.01, 0.087}));
  }
  config.seed = 1;
  emit("track-box", track_sequence_global(seq, mesh, config, projected_box(mesh, seq.camera, truth)));
  for (double gap : {0.5, 2.0}) {
    Sequence stalled = seq;
    for (size_t i = 6; i < stalled.frames.size(); ++i) stalled.frames[i].timestamp += gap;
    emit(gap < 1 ? "track-gap0.5" : "track-gap2",
         track_sequence(stalled, mesh, config, perturb_pose(truth, centre, 0.01, 5, 1), {0.01, 0.087}));
  }
}

}  // namespace

int main(int argc, char** argv) try {
  const Options o = parse(argc, argv);
  const std::vector<std::string> names = o.objects.empty() ? clip_objects(o.clip) : o.objects;
  std::mt19937_64 rng(o.seed);
  TrackerConfig config;
  config.width = o.size.first;
  config.height = o.size.second;
  config.refine.iterations = 16;  // as the search's fit of its candidates
  std::printf(
      "clip,object,frame,kind,start_mm,start_deg,adds_mm,diameter_mm,pixels,visible,occluded,contradicted,missing,"
      "separated,outline_nearer,visible_rms,plane_rms,confidence,status\n");
  // Every object's sequence (the same frames, each with its own truth) for placing one on another.
  std::vector<Sequence> sequences;
  std::vector<std::string> found;
  for (const auto& name : names) {
    if (mesh_path(o.mesh_dir, name).empty()) continue;
    sequences.push_back(load_sequence(o.clip, name));
    found.push_back(name);
  }
  std::vector<Eigen::Vector3d> other_centres;
  for (const auto& name : found)
    other_centres.push_back(Mesh::load(mesh_path(o.mesh_dir, name)).centre().cast<double>());
  const std::string clip_name = std::filesystem::path(o.clip).filename().string();
  for (size_t k = 0; k < found.size(); ++k) {
    const Sequence& seq = sequences[k];
    const Mesh mesh = Mesh::load(mesh_path(o.mesh_dir, found[k]));
    const Mesh drawn = simplify_for_drawing(mesh, config.simplify_error).mesh;
    const int decimation = seq.camera.decimation_factor_for(config.width, config.height);
    const Camera working = seq.camera.decimated(decimation);
    const reference::PoseRefiner refiner(drawn, working, config);
    const reference::Rasterizer rasterizer(drawn, working, config.near_plane, config.observation.max_depth);
    const AddsMetric adds(mesh);
    const Eigen::Vector3d centre = mesh.centre().cast<double>();
    const double diameter = 2.0 * mesh.radius();
    std::vector<float> scratch(static_cast<size_t>(working.pixel_count()));
    const std::vector<double> fresh(static_cast<size_t>(working.pixel_count()), model::fresh_occlusion(config));
    if (o.track) {
      track_rows(clip_name, found[k], seq, mesh, config, diameter);
      continue;
    }
    for (size_t f = 0; f < seq.frames.size(); f += static_cast<size_t>(o.every)) {
      if (!seq.frames[f].ground_truth) continue;
      const Pose truth = *seq.frames[f].ground_truth;
      const DepthImage depth = seq.load_depth(f).decimated(decimation);
      std::vector<Sample> samples{{"truth", truth}};
      const double metres[] = {0.002, 0.005, 0.01, 0.02, 0.04, 0.08, 0.15};
      const double degrees[] = {0, 5, 15, 45, 120};
      for (double m : metres)
        for (double d : degrees) samples.push_back({"perturbed", perturb_pose(truth, centre, m, d, rng())});
      // On another object: its centre where the other's is, turned at random.
      for (size_t j = 0; j < found.size(); ++j) {
        if (j == k || !sequences[j].frames[f].ground_truth) continue;
        const Pose other = *sequences[j].frames[f].ground_truth;
        const Eigen::Vector3d other_centre = other.rotation * other_centres[j] + other.translation;
        for (int r = 0; r < 3; ++r) {
          Pose p;
          p.rotation = Eigen::Quaterniond::UnitRandom();
          p.translation = other_centre - p.rotation * centre;
          samples.push_back({"other", p});
        }
      }
      // On the scene: the centre a radius behind a random measured pixel, turned at random.
      for (int r = 0; r < 12; ++r) {
        std::uniform_int_distribution<int> pick(0, working.pixel_count() - 1);
        int i = pick(rng);
        for (int tries = 0; tries < 100 && !DepthImage::is_valid(depth.data()[static_cast<size_t>(i)]); ++tries)
          i = pick(rng);
        const double z = depth.data()[static_cast<size_t>(i)];
        if (!DepthImage::is_valid(static_cast<float>(z))) continue;
        const int u = i % working.width, v = i / working.width;
        const Eigen::Vector3d ray((u - working.cx) / working.fx, (v - working.cy) / working.fy, 1.0);
        Pose p;
        p.rotation = Eigen::Quaterniond::UnitRandom();
        p.translation = ray * z + Eigen::Vector3d(0, 0, 0.5 * mesh.radius()) - p.rotation * centre;
        samples.push_back({"scene", p});
      }
      for (const Sample& s : samples) {
        const double start_mm =
            1000.0 *
            ((s.pose.rotation * centre + s.pose.translation) - (truth.rotation * centre + truth.translation)).norm();
        const double start_deg = s.pose.rotation.angularDistance(truth.rotation) * 180.0 / M_PI;
        const reference::RefinedPose fit = refiner.refine(s.pose, depth, fresh);
        const SilhouetteShares sh =
            silhouette_shares(rasterizer, config.observation, config.loss.pixel_sigmas, fit.pose, depth, scratch);
        print_row(clip_name, found[k], seq.frames[f].name, s.kind, start_mm, start_deg, adds(fit.pose, truth), diameter,
                  sh, pose_confidence(sh), "-");
      }
      std::fflush(stdout);
    }
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "depthtrack_confidence_samples: %s\n", e.what());
  return 1;
}
