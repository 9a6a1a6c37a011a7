// depthtrack track: run the tracker over a recorded sequence and write the estimates as CSV.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/frame_source.hpp>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>

#include "cli/candidates_csv.hpp"
#include "cli/commands.hpp"
#include "cli/init_spread.hpp"
#include "cli/mesh_scale_warning.hpp"
#include "cli/overlay_writer.hpp"
#include "cli/progress.hpp"
#include "cli/run_summary.hpp"
#include "cli/staged_outputs.hpp"
#include "cli/tracker_options.hpp"
#include "core/mesh_simplify.hpp"
#include "core/mesh_topology.hpp"
#include "io/sequence_formats.hpp"

namespace depthtrack::cli {

namespace {

struct TrackArgs {
  std::vector<std::string> meshes, objects;  // in pairs when there are several
  std::string mutual_occlusion = "on";
  std::string mesh, sequence, source, frames, out, object, init, init_perturb,
      init_spread = default_init_spread(), init_box, summary, overlay, bop_out, candidates_out;
  std::string quaternion = "wxyz";
  double unit_scale = 1.0;
  bool init_from_gt = false, init_global = false, no_recover = false;
  CLI::Option* unit_scale_option = nullptr;  // to tell an explicit --unit-scale from the default
  TrackerOptions tracker;
};

QuaternionOrder quaternion_order(const std::string& name) {
  if (name == "wxyz") return QuaternionOrder::Wxyz;
  if (name == "xyzw") return QuaternionOrder::Xyzw;
  throw InputError("--quaternion '" + name + "' is neither wxyz (depthtrack, Eigen) nor xyzw (ROS)");
}

Pose initial_pose(const TrackArgs& a, const Sequence& seq, const Mesh& mesh, uint64_t seed) {
  if (!a.init.empty()) {
    const auto v = parse_numbers(a.init, 7, "--init");
    if (quaternion_order(a.quaternion) == QuaternionOrder::Xyzw)
      return Pose({v[0], v[1], v[2]}, Eigen::Quaterniond(v[6], v[3], v[4], v[5]));
    return Pose({v[0], v[1], v[2]}, Eigen::Quaterniond(v[3], v[4], v[5], v[6]));
  }
  if (seq.frames.empty() || !seq.frames.front().ground_truth)
    throw InputError("--init-from-gt: the first frame of '" + (a.sequence.empty() ? a.source : a.sequence) +
                     "' has no ground truth" + (seq.object.empty() ? "" : " for object '" + seq.object + "'"));
  Pose pose = *seq.frames.front().ground_truth;
  if (!a.init_perturb.empty()) {
    const auto v = parse_numbers(a.init_perturb, 2, "--init-perturb");
    pose = perturb_pose(pose, mesh.centre().cast<double>(), v[0], v[1], seed);
  }
  return pose;
}

void print_summary(const RunStats& s, const TrackedFrame* last) {
  std::printf("%zu frames in %.2f s: %.1f frames per second\n", s.frames, s.seconds, s.frames_per_second);
  if (!s.ground_truth || !last) return;
  const double deg = 180.0 / std::numbers::pi;
  std::printf("translation error: mean %.2f mm, max %.2f mm; rotation error: mean %.2f deg; ADD-S: mean %.2f mm\n",
              s.mean_err_t_mm, s.max_err_t_mm, s.mean_err_r_deg, s.mean_adds_mm);
  std::printf("last frame: translation %.2f mm, rotation %.2f deg, ADD-S %.2f mm\n", 1000 * last->translation_error,
              deg * last->rotation_error, 1000 * last->adds);
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

// The mesh, with notes on what the tracker will draw of it: degenerate triangles dropped, how far the
// default (or given) simplification thins it (TrackerConfig::simplify_error), and whether its back faces
// can be culled (an open scan's cannot), so that a run's speed and a fine mesh's precision are not a surprise.
Mesh load_mesh(const std::string& path, double unit_scale, const TrackerConfig& config) {
  const ProgressWait wait("reading and checking '" + path + "'");
  const Mesh mesh = Mesh::load(path, unit_scale);
  warn_if_mesh_scale_unusual(mesh, path, unit_scale);
  if (mesh.dropped_degenerate > 0)
    std::fprintf(stderr, "depthtrack: note: dropped %zu degenerate triangles of '%s'\n", mesh.dropped_degenerate,
                 path.c_str());
  Mesh checked = mesh;
  checked.validate_and_clean(path);
  const MeshSimplification drawing = config.budget_ms > 0 ? simplify_for_budget(checked, config.simplify_error)
                                                          : simplify_for_drawing(checked, config.simplify_error);
  const Mesh& drawn = drawing.mesh;
  // A budget's coarser drawing (simplify_for_budget) is reported by its own estimate of the error.
  const double within = std::max(drawing_error(checked, config.simplify_error), drawing.error);
  if (drawn.triangles.size() < checked.triangles.size())
    std::fprintf(stderr,
                 "depthtrack: note: drawing '%s' simplified within %g mm: %zu of its %zu triangles "
                 "(--simplify-error 0 draws it as given)\n",
                 path.c_str(), within * 1e3, drawn.triangles.size(), checked.triangles.size());
  if (!bounds_solid_outward(drawn))
    std::fprintf(stderr,
                 "depthtrack: note: '%s' does not bound a solid wound outward (an edge without its reverse, or a "
                 "part wound inward), so every triangle is drawn facing either way: about twice the drawing of a "
                 "closed mesh\n",
                 path.c_str());
  return mesh;
}

// Where the frames come from: a folder (--sequence DIR, --source folder:DIR or --source DIR) or another kind of
// source (--source raw:-), which is read as a stream.
struct FramesFrom {
  std::string spec;              // as given, for messages and the summary
  std::filesystem::path folder;  // set for a folder
  std::string location;          // the stream's location (after "KIND:") otherwise
  bool is_folder() const { return !folder.empty(); }
};

FramesFrom frames_from(const TrackArgs& a) {
  if (a.sequence.empty() == a.source.empty())
    throw InputError(a.sequence.empty() ? "give the frames: --sequence DIR or --source KIND:LOCATION (e.g. raw:-)"
                                        : "--sequence and --source exclude each other: give one");
  if (!a.sequence.empty()) return {a.sequence, a.sequence, ""};
  for (const auto& [kind, description] : frame_source_kinds()) {
    const std::string prefix = kind + ":";
    if (a.source.rfind(prefix, 0) != 0) continue;
    if (kind == "folder") return {a.source, a.source.substr(prefix.size()), ""};
    return {a.source, "", a.source.substr(prefix.size())};
  }
  // A folder; or, when no such path exists and it reads KIND:..., a kind open_frame_source names as unknown.
  std::error_code error;
  if (a.source.find(':') != std::string::npos && !std::filesystem::exists(a.source, error))
    return {a.source, "", a.source};
  return {a.source, a.source, ""};
}

// The files a run reads, which no output may name: the meshes, the --config file, the sequence's manifests
// (before loading it) or the stream's file and, once loaded, each frame's images.
void add_argument_inputs(const TrackArgs& a, const FramesFrom& from, StagedOutputs& outputs) {
  for (const std::string& mesh : a.meshes) outputs.add_input(mesh);
  outputs.add_input(a.tracker.config_file);
  if (!from.is_folder()) {
    if (from.location != "-") outputs.add_input(from.location);
    return;
  }
  for (const char* manifest :
       {io::kDepthtrackManifest, io::kYcbVideoManifest, io::kBopManifest, "scene_gt.json", "scene_gt_info.json"})
    outputs.add_input(from.folder / manifest);
}

// The folder's sequence, cut to --frames when given.
Sequence load_frames(const TrackArgs& a, const FramesFrom& from, const std::string& object) {
  const Sequence seq = load_sequence(from.folder, object);
  if (a.frames.empty()) return seq;
  const FrameRange range = parse_frame_range(a.frames);
  try {
    return frames_in(seq, range);
  } catch (const InputError& e) {
    throw InputError("--frames " + a.frames + ": " + e.what());
  }
}

void add_sequence_inputs(const Sequence& sequence, StagedOutputs& outputs) {
  for (const SequenceFrame& f : sequence.frames) {
    outputs.add_input(f.depth_path);
    outputs.add_input(f.colour_path);
  }
}

bool on_off(const std::string& value, const std::string& option) {
  if (value == "on") return true;
  if (value == "off") return false;
  throw InputError(option + " takes on or off, not '" + value + "'");
}

// Several objects (--mesh/--object pairs): one Device, an `object` column first, a row per object per frame.
void run_track_objects(const TrackArgs& a) {
  if (a.objects.size() != a.meshes.size())
    throw InputError("several objects need --mesh and --object in pairs: got " + std::to_string(a.meshes.size()) +
                     " --mesh and " + std::to_string(a.objects.size()) + " --object");
  if (!a.init_from_gt)
    throw InputError("several objects start from their ground truth: give --init-from-gt (and --init-perturb)");
  for (const auto& [set, name] : {std::pair{!a.init.empty(), "--init"},
                                  {!a.init_box.empty(), "--init-box"},
                                  {a.init_global, "--init-global"},
                                  {!a.bop_out.empty(), "--bop-out"},
                                  {!a.candidates_out.empty(), "--candidates-out"}})
    if (set) throw InputError(std::string(name) + " is for one object; not with several --mesh/--object pairs");
  const bool mutual = on_off(a.mutual_occlusion, "--mutual-occlusion");
  const FramesFrom from = frames_from(a);
  if (!from.is_folder())
    throw InputError("several objects are tracked through a sequence folder, not through '" + from.spec + "'");
  StagedOutputs outputs;
  add_argument_inputs(a, from, outputs);
  const std::filesystem::path csv_path = outputs.add("--out", a.out);
  const std::filesystem::path summary_path =
      a.summary.empty() || a.summary == "-" ? std::filesystem::path(a.summary) : outputs.add("--summary", a.summary);
  TrackerConfig config = a.tracker.resolve();
  if (a.no_recover) config.recovery.enabled = false;
  std::vector<TrackedObject> objects;
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    TrackArgs one = a;
    one.object = a.objects[i];
    TrackedObject o{a.objects[i], {}, load_frames(a, from, a.objects[i]), {}};
    add_sequence_inputs(o.sequence, outputs);
    const bool bop_units = o.sequence.format == "bop" && a.unit_scale_option->count() == 0;
    o.mesh = load_mesh(a.meshes[i], bop_units ? 0.001 : a.unit_scale, config);
    o.initial = initial_pose(one, o.sequence, o.mesh, config.seed);  // as the object's own run starts
    objects.push_back(std::move(o));
  }
  const auto& frames0 = objects.front().sequence.frames;
  const bool with_truth = std::all_of(objects.begin(), objects.end(), [](const TrackedObject& o) {
    return std::all_of(o.sequence.frames.begin(), o.sequence.frames.end(),
                       [](const auto& f) { return f.ground_truth.has_value(); });
  });
  TrackingCsvWriter csv(csv_path, with_truth && !frames0.empty(), quaternion_order(a.quaternion), true);
  const InitialSpread spread = parse_init_spread(a.init_spread);
  // Every object's estimate on one picture per frame, drawn once the frame's last object is tracked.
  std::optional<OverlayWriter> overlay;
  std::vector<const Mesh*> meshes;
  std::vector<std::string> names;
  for (const TrackedObject& o : objects) {
    meshes.push_back(&o.mesh);
    names.push_back(o.name);
  }
  if (!a.overlay.empty())
    overlay.emplace(stage_overlay(a.overlay, objects.front().sequence, outputs), meshes, objects.front().sequence);
  std::vector<TrackedFrame> current(objects.size());
  double overlay_seconds = 0;
  ProgressBar bar("tracking", static_cast<int>(frames0.size()));
  const auto begin = std::chrono::steady_clock::now();
  std::optional<ProgressWait> preparing(std::in_place, "preparing the models");  // until the first frame is out
  const auto results = track_objects(objects, config, spread, mutual, [&](size_t i, size_t j, const TrackedFrame& f) {
    preparing.reset();
    csv.write(f, objects[j].name);
    if (j + 1 < objects.size()) {
      if (overlay) current[j] = f;
      return;
    }
    bar.update(static_cast<int>(i + 1), "");
    if (!overlay) return;
    const auto drawing = std::chrono::steady_clock::now();
    current[j] = f;
    std::vector<const TrackedFrame*> frames;
    for (const TrackedFrame& c : current) frames.push_back(&c);
    overlay->write(i, frames, names, config.particles);
    overlay_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - drawing).count();
  });
  // Frames per second of the tracking, not of drawing the pictures.
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count() - overlay_seconds;
  bar.finish();
  csv.finish();
  if (!a.summary.empty()) {
    std::vector<ObjectStats> stats;
    for (size_t j = 0; j < objects.size(); ++j)
      stats.push_back({objects[j].name, a.meshes[j], run_stats(results[j], seconds)});
    write_summary(summary_path, objects_summary_json(stats, frames0.size(), seconds, config, a.sequence));
  }
  outputs.commit();
  std::printf("%zu objects, %zu frames in %.2f s: %.1f frames per second (mutual occlusion %s)\n", objects.size(),
              frames0.size(), seconds, seconds > 0 ? static_cast<double>(frames0.size()) / seconds : 0.0,
              mutual ? "on" : "off");
  for (size_t j = 0; j < objects.size(); ++j)
    if (!results[j].empty() && results[j].back().ground_truth)
      std::printf("%s: last frame translation %.2f mm, rotation %.2f deg, ADD-S %.2f mm\n", objects[j].name.c_str(),
                  1000 * results[j].back().translation_error,
                  180.0 / std::numbers::pi * results[j].back().rotation_error, 1000 * results[j].back().adds);
  std::printf("wrote %s\n", a.out.c_str());
}

// A stream's restrictions: what needs the frames beforehand (ground truth, names, files) is refused.
void check_stream_options(const TrackArgs& a, const FramesFrom& from) {
  if (a.init_from_gt)
    throw InputError("--init-from-gt needs the first frame's ground truth beforehand, which '" + from.spec +
                     "' does not give: start with --init, --init-box or --init-global");
  for (const auto& [set, name] : {std::pair{!a.overlay.empty(), "--overlay"}, {!a.bop_out.empty(), "--bop-out"}})
    if (set) throw InputError(std::string(name) + " is for a sequence folder, not for '" + from.spec + "'");
}

void run_track(TrackArgs a) {
  if (a.meshes.size() > 1 || a.objects.size() > 1) return run_track_objects(a);
  a.mesh = a.meshes.empty() ? "" : a.meshes.front();
  a.object = a.objects.empty() ? "" : a.objects.front();
  const int starts = !a.init.empty() + a.init_from_gt + !a.init_box.empty() + a.init_global;
  if (starts == 0) throw InputError("give --init POSE, --init-from-gt, --init-box \"u0 v0 u1 v1\" or --init-global");
  if (starts > 1) throw InputError("--init, --init-from-gt, --init-box and --init-global exclude each other");
  if (!a.candidates_out.empty() && a.init_box.empty() && !a.init_global)
    throw InputError("--candidates-out lists the first frame's search candidates: give --init-global or --init-box");
  const QuaternionOrder order = quaternion_order(a.quaternion);
  const FramesFrom from = frames_from(a);
  if (!from.is_folder()) check_stream_options(a, from);
  const std::optional<FrameRange> range =
      a.frames.empty() ? std::nullopt : std::optional<FrameRange>(parse_frame_range(a.frames));
  // Every output is checked before any work and written beside its place; all replace the earlier files
  // together once the run succeeded (outputs.commit()), none when it fails.
  StagedOutputs outputs;
  add_argument_inputs(a, from, outputs);
  const std::filesystem::path csv_path = outputs.add("--out", a.out);
  const std::filesystem::path bop_path = a.bop_out.empty() ? "" : outputs.add("--bop-out", a.bop_out);
  const std::filesystem::path candidates_path =
      a.candidates_out.empty() ? "" : outputs.add("--candidates-out", a.candidates_out);
  const std::filesystem::path summary_path =
      a.summary.empty() || a.summary == "-" ? std::filesystem::path(a.summary) : outputs.add("--summary", a.summary);
  TrackerConfig config = a.tracker.resolve();
  if (a.no_recover) config.recovery.enabled = false;  // else as the --config file says
  // A folder is loaded whole (its ground truth, names and files known beforehand); any other source is
  // opened as a stream, read frame by frame.
  std::optional<Sequence> seq;
  std::unique_ptr<FrameSource> source;
  if (from.is_folder()) {
    seq = load_frames(a, from, a.object);
    add_sequence_inputs(*seq, outputs);
    if (!a.bop_out.empty()) check_bop_exportable(*seq);
  } else {
    source = open_frame_source(from.spec, FrameSourceOptions{a.object});
    if (range) source = frames_in(std::move(source), *range);
  }
  const std::vector<std::filesystem::path> overlay_files =
      a.overlay.empty() ? std::vector<std::filesystem::path>{} : stage_overlay(a.overlay, *seq, outputs);
  // Rows are streamed as frames are tracked.
  TrackingCsvWriter csv(
      csv_path,
      seq && !seq->frames.empty() &&
          std::all_of(seq->frames.begin(), seq->frames.end(), [](const auto& f) { return f.ground_truth.has_value(); }),
      order);
  // BOP models are in millimetres by the format's definition.
  const bool bop_units = seq && seq->format == "bop" && a.unit_scale_option->count() == 0;
  const double unit_scale = bop_units ? 0.001 : a.unit_scale;
  if (bop_units)
    std::fprintf(stderr, "depthtrack: note: BOP scene: reading the mesh in millimetres (--unit-scale 0.001)\n");
  const Mesh mesh = load_mesh(a.mesh, unit_scale, config);
  const bool global = !a.init_box.empty() || a.init_global;
  const InitHint hint = init_hint(a);
  const InitialSpread spread = parse_init_spread(a.init_spread);
  const Pose initial = global ? Pose()
                       : seq  ? initial_pose(a, *seq, mesh, config.seed)
                              : initial_pose(a, Sequence{}, mesh, 0);

  std::optional<OverlayWriter> overlay;
  if (!a.overlay.empty()) overlay.emplace(overlay_files, std::vector<const Mesh*>{&mesh}, *seq);
  double overlay_seconds = 0;

  if (seq) source = sequence_source(*seq);  // decoding starts while the tracker starts up
  ProgressBar bar("tracking", static_cast<int>(source->size().value_or(0)));
  const auto begin = std::chrono::steady_clock::now();
  // Until the first frame is out: the model's preparation and, with --init-box or --init-global, the search.
  std::optional<ProgressWait> preparing(
      std::in_place,
      global ? "preparing the model and searching the first frame for the object" : "preparing the model");
  const auto on_frame = [&](size_t i, const TrackedFrame& f) {
    preparing.reset();
    csv.write(f);
    char text[64] = "";
    if (f.ground_truth) std::snprintf(text, sizeof text, "err %.1f mm", 1000 * f.translation_error);
    bar.update(static_cast<int>(i + 1), text);
    if (!overlay) return;
    const auto drawing = std::chrono::steady_clock::now();
    overlay->write(i, f, config.particles);
    overlay_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - drawing).count();
  };
  std::vector<SearchCandidate> candidates;
  const auto frames = global ? track_source_global(*source, mesh, config, hint, candidates, on_frame)
                             : track_source(*source, mesh, config, initial, spread, on_frame);
  // Frames per second of the tracking, not of drawing the pictures.
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count() - overlay_seconds;
  bar.finish();
  csv.finish();
  if (!a.bop_out.empty()) write_bop_csv(bop_path, *seq, frames);
  if (!a.candidates_out.empty()) write_candidates_csv(candidates_path, candidates, order);
  const RunStats stats = run_stats(frames, seconds);
  if (!a.summary.empty()) write_summary(summary_path, summary_json(stats, config, from.spec, a.mesh));
  outputs.commit();
  print_summary(stats, frames.empty() ? nullptr : &frames.back());
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
  c->add_option("--mesh", args->meshes,
                "Object mesh (OBJ, PLY, STL, glTF, ... through assimp); repeat it with --object for several objects "
                "in one run (--mesh A --object a --mesh B --object b: one device, an object column first in the "
                "CSV, a row per object per frame)")
      ->required()
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  args->unit_scale_option =
      c->add_option("--unit-scale", args->unit_scale,
                    "Multiply mesh coordinates by this to get metres (default 1; 0.001 for a BOP scene, whose "
                    "models are in mm)");
  c->add_option("--sequence", args->sequence,
                "Sequence folder: depthtrack's own (sequence.json, what `depthtrack synth` writes; 16-bit PNG or "
                "float32 .f32 depth), a YCB-Video clip (NNNNNN-depth.png + gt.json), a BOP scene "
                "(scene_camera.json, scene_gt.json, depth/) or a ViSP simulated sequence (Depth/, CameraPose/, "
                "Config/); or give --source");
  c->add_option("--source", args->source,
                std::string("Where the frames come from instead of --sequence: folder:DIR, or raw:FILE, raw:FIFO or "
                            "raw:- (stdin) for the raw depth stream, read as it arrives (no ground truth; start with "
                            "--init, --init-box or --init-global). ") +
                    raw_stream_format());
  c->add_option("--frames", args->frames,
                "Track only frames A:B: A up to but not including B, counted from 0 (A: to the end, :B the first "
                "B); a range past the sequence's end is an error");
  c->add_option("--out", args->out,
                "CSV to write: frame,timestamp,tx,ty,tz,qw,qx,qy,qz,ess (camera-from-object, metres), plus "
                "err_t_mm,err_r_deg,adds_mm when ground truth is known, then latency_ms (depth in to pose out), "
                "confidence,status (tracking, lost, no-data); written to FILE.partial and renamed when all frames "
                "are done")
      ->required();
  c->add_option("--summary", args->summary,
                "Also write a one-line JSON summary of the run (frames, mean/max errors, fps, backend) to this "
                "file; - prints it. With several objects: the run's figures and an `objects` array, one entry "
                "(object, mesh, frames, mean/max errors) per object");
  c->add_option("--overlay", args->overlay,
                "Also draw each frame's estimate (silhouette, outline, depth edges) over its colour image, or "
                "its depth in colour, with frame, error and ESS, as DIR/<frame>.png (DIR is created); with several "
                "objects, all of them on each picture, a text line per object");
  c->add_option("--quaternion", args->quaternion,
                "Quaternion component order of --init and the CSV: wxyz (depthtrack, Eigen) or xyzw (ROS, tf2)")
      ->capture_default_str();
  c->add_option("--object", args->objects,
                "Which object's ground truth to use in a multi-object clip: a YCB-Video name (e.g. 025_mug) or a "
                "BOP obj_id; one per --mesh when there are several")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  c->add_option("--mutual-occlusion", args->mutual_occlusion,
                "With several objects: the pixels the other objects' latest estimates hide are missing for each "
                "object (on) or not (off)")
      ->capture_default_str();
  c->add_option("--bop-out", args->bop_out,
                "Also write the estimates as BOP results: scene_id,im_id,obj_id,score,R,t,time (R row-major, t in "
                "mm; BOP scenes only)");
  c->add_option("--init", args->init,
                "Initial pose \"tx ty tz qw qx qy qz\" (camera-from-object, metres; qx qy qz qw with --quaternion "
                "xyzw)");
  c->add_flag("--init-from-gt", args->init_from_gt, "Start from the first frame's ground-truth pose");
  c->add_option("--init-box", args->init_box,
                "Find the object inside this box of the first frame: \"u0 v0 u1 v1\", inclusive sensor pixels "
                "(what a detector gives); no pose needed");
  c->add_flag("--init-global", args->init_global, "Find the object anywhere in the first frame; no pose needed");
  c->add_option("--candidates-out", args->candidates_out,
                "With --init-global or --init-box: also write the first frame's search candidates, best first: "
                "rank,score,confidence,tx,ty,tz and the quaternion (score: log-likelihood; confidence: the "
                "probability the pose lies within tolerance)");
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
