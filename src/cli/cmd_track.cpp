// depthtrack track: run the tracker over a recorded sequence and write the estimates as CSV.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <iostream>
#include <memory>
#include <numbers>

#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "cli/tracker_options.hpp"

namespace depthtrack::cli {

namespace {

struct TrackArgs {
  std::string mesh, sequence, out, object, init, init_perturb, init_spread = "0.01 5", init_box;
  double unit_scale = 1.0;
  bool init_from_gt = false, init_global = false, no_recover = false;
  TrackerOptions tracker;
};

Pose initial_pose(const TrackArgs& a, const Sequence& seq, const Mesh& mesh) {
  if (!a.init.empty()) {
    const auto v = parse_numbers(a.init, 7, "--init");
    return Pose({v[0], v[1], v[2]}, Eigen::Quaterniond(v[3], v[4], v[5], v[6]));
  }
  if (seq.frames.empty() || !seq.frames.front().ground_truth)
    throw InputError("--init-from-gt: the first frame of '" + a.sequence + "' has no ground truth" +
                     (seq.object.empty() ? "" : " for object '" + seq.object + "'"));
  Pose pose = *seq.frames.front().ground_truth;
  if (!a.init_perturb.empty()) {
    const auto v = parse_numbers(a.init_perturb, 2, "--init-perturb");
    pose = perturb_pose(pose, mesh.centre().cast<double>(), v[0], v[1], a.tracker.config.seed);
  }
  return pose;
}

void print_summary(const std::vector<TrackedFrame>& frames, const Mesh& mesh, double seconds) {
  std::printf("%zu frames in %.2f s: %.1f frames per second\n", frames.size(), seconds,
              static_cast<double>(frames.size()) / seconds);
  if (frames.empty() || !frames.back().ground_truth) return;
  double sum_t = 0, sum_r = 0, max_t = 0;
  for (const auto& f : frames) {
    sum_t += f.translation_error;
    sum_r += f.rotation_error;
    max_t = std::max(max_t, f.translation_error);
  }
  const double n = static_cast<double>(frames.size()), deg = 180.0 / std::numbers::pi;
  const TrackedFrame& last = frames.back();
  std::printf("translation error: mean %.2f mm, max %.2f mm; rotation error: mean %.2f deg\n", 1000 * sum_t / n,
              1000 * max_t, deg * sum_r / n);
  std::printf("last frame: translation %.2f mm, rotation %.2f deg, ADD-S %.2f mm\n", 1000 * last.translation_error,
              deg * last.rotation_error, 1000 * AddsMetric(mesh)(last.estimate.pose, *last.ground_truth));
}

// The hint of --init-box (inclusive sensor pixels of the first frame) or --init-global (none).
InitHint init_hint(const TrackArgs& a) {
  if (a.init_box.empty()) return InitHint::anywhere();
  const auto v = parse_numbers(a.init_box, 4, "--init-box");
  for (double x : v)
    if (x != std::floor(x))
      throw InputError("--init-box takes whole pixel numbers \"u0 v0 u1 v1\", got '" + a.init_box + "'");
  return InitHint::box(static_cast<int>(v[0]), static_cast<int>(v[1]), static_cast<int>(v[2]), static_cast<int>(v[3]));
}

void run_track(const TrackArgs& a) {
  const int starts = !a.init.empty() + a.init_from_gt + !a.init_box.empty() + a.init_global;
  if (starts == 0) throw InputError("give --init POSE, --init-from-gt, --init-box \"u0 v0 u1 v1\" or --init-global");
  if (starts > 1) throw InputError("--init, --init-from-gt, --init-box and --init-global exclude each other");
  TrackerConfig config = a.tracker.resolve();
  config.recovery.enabled = !a.no_recover;
  const Mesh mesh = Mesh::load(a.mesh, a.unit_scale);
  if (mesh.dropped_degenerate > 0)
    std::fprintf(stderr, "depthtrack: note: dropped %zu degenerate triangles of '%s'\n", mesh.dropped_degenerate,
                 a.mesh.c_str());
  const Sequence seq = load_sequence(a.sequence, a.object);
  const bool global = !a.init_box.empty() || a.init_global;
  const InitHint hint = init_hint(a);
  const auto spread_values = parse_numbers(a.init_spread, 2, "--init-spread");
  const InitialSpread spread{spread_values[0], spread_values[1] * std::numbers::pi / 180.0};

  ProgressBar bar("tracking", static_cast<int>(seq.frames.size()));
  const auto begin = std::chrono::steady_clock::now();
  const auto progress = [&](size_t i, const TrackedFrame& f) {
    char text[64] = "";
    if (f.ground_truth) std::snprintf(text, sizeof text, "err %.1f mm", 1000 * f.translation_error);
    bar.update(static_cast<int>(i + 1), text);
  };
  const auto frames = global ? track_sequence_global(seq, mesh, config, hint, progress)
                             : track_sequence(seq, mesh, config, initial_pose(a, seq, mesh), spread, progress);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  bar.finish();
  write_tracking_csv(a.out, frames);
  print_summary(frames, mesh, seconds);
  if (global && !frames.empty())
    std::printf("global initialization: %.2f s, %zu poses scored\n", frames.front().estimate.timings.search_ms / 1000,
                frames.front().estimate.search_poses);
  const auto lost = std::count_if(frames.begin(), frames.end(),
                                  [](const TrackedFrame& f) { return f.estimate.status == TrackStatus::Lost; });
  if (lost > 0) std::printf("lost in %lld of %zu frames\n", static_cast<long long>(lost), frames.size());
  std::printf("wrote %s\n", a.out.c_str());
}

}  // namespace

void add_track_command(CLI::App& app) {
  auto args = std::make_shared<TrackArgs>();
  CLI::App* c = app.add_subcommand("track", "Track an object through a depth sequence and write the poses as CSV");
  c->add_option("--mesh", args->mesh, "Object mesh (OBJ, PLY, STL, glTF, ... through assimp)")->required();
  c->add_option("--unit-scale", args->unit_scale, "Multiply mesh coordinates by this to get metres")
      ->capture_default_str();
  c->add_option("--sequence", args->sequence,
                "Sequence folder: depthtrack's own (sequence.json, what `depthtrack synth` writes) or a "
                "YCB-Video clip (NNNNNN-depth.png + gt.json)")
      ->required();
  c->add_option("--out", args->out,
                "CSV to write: frame,timestamp,tx,ty,tz,qw,qx,qy,qz,ess (camera-from-object, metres), plus "
                "err_t_mm,err_r_deg when ground truth is known, then confidence,status")
      ->required();
  c->add_option("--object", args->object, "Which object's ground truth to use in a multi-object clip (e.g. 025_mug)");
  c->add_option("--init", args->init, "Initial pose \"tx ty tz qw qx qy qz\" (camera-from-object, metres)");
  c->add_flag("--init-from-gt", args->init_from_gt, "Start from the first frame's ground-truth pose");
  c->add_option("--init-box", args->init_box,
                "Find the object inside this box of the first frame: \"u0 v0 u1 v1\", inclusive sensor pixels "
                "(what a detector gives); no pose needed");
  c->add_flag("--init-global", args->init_global, "Find the object anywhere in the first frame; no pose needed");
  c->add_flag("--no-recover", args->no_recover,
              "Do not search for the object again while it is lost (status stays lost until the filter finds it)");
  c->add_option("--init-perturb", args->init_perturb,
                "With --init-from-gt: move the start by exactly \"METRES DEGREES\" in a seeded random direction");
  c->add_option("--init-spread", args->init_spread,
                "Standard deviation \"METRES DEGREES\" of the initial particle cloud, per axis")
      ->capture_default_str();
  args->tracker.add_to(*c);
  c->callback([args] { run_track(*args); });
}

}  // namespace depthtrack::cli
