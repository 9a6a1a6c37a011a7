// depthtrack eval: how accurate and how trustworthy the tracker is on a clip with ground truth, per object
// and per start (perturbed ground truth, a 2D box, a stall in the timestamps).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>

#include "cli/commands.hpp"
#include "cli/eval_frames_csv.hpp"
#include "cli/eval_report.hpp"
#include "cli/init_spread.hpp"
#include "cli/mesh_scale_warning.hpp"
#include "cli/progress.hpp"
#include "cli/python_plots.hpp"
#include "cli/staged_outputs.hpp"
#include "cli/tracker_options.hpp"
#include "eval/clip_objects.hpp"
#include "eval/label_box.hpp"

namespace depthtrack::cli {

namespace {

namespace fs = std::filesystem;

// The perturbed start: ground truth moved by exactly this much.
constexpr double kPerturbMetres = 0.01, kPerturbDegrees = 5.0;

struct EvalArgs {
  std::string sequence, mesh_dir, mesh, cases = "perturbed,box,gap", gaps = "0.5,2", frames_out, reliability,
                                        init_spread = default_init_spread();
  std::vector<std::string> objects;
  int seeds = 3, gap_before = 6;
  double unit_scale = 1.0;
  bool no_recover = false;
  CLI::Option* unit_scale_option = nullptr;
  TrackerOptions tracker;
};

struct EvalCase {
  CaseKind kind = CaseKind::Perturbed;
  std::string name;
  uint64_t seed = 1;  // Perturbed and Gap: perturb_pose's
  double gap = 0;     // Gap: seconds added to every timestamp from --gap-before on
};

struct EvalObject {
  std::string name;           // as printed
  std::string sequence_name;  // load_sequence's object
  fs::path mesh_path;
  Mesh mesh;
  Sequence sequence;
  MeshDiameter diameter;
  double tolerance = 0;
  InitHint box;
  std::string box_source;  // "label" or "projected"; empty without a box case
};

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) items.push_back(item);
  return items;
}

std::vector<EvalCase> eval_cases(const EvalArgs& a) {
  const auto kinds = split_list(a.cases);
  if (kinds.empty()) throw InputError("--cases is empty: give some of perturbed, box, gap");
  for (const auto& k : kinds)
    if (k != "perturbed" && k != "box" && k != "gap")
      throw InputError("--cases: unknown case '" + k + "' (perturbed, box, gap)");
  const auto wants = [&](const char* k) { return std::find(kinds.begin(), kinds.end(), k) != kinds.end(); };
  if (a.seeds < 1) throw InputError("--seeds must be at least 1, got " + std::to_string(a.seeds));
  std::vector<EvalCase> cases;
  if (wants("perturbed"))
    for (int s = 1; s <= a.seeds; ++s)
      cases.push_back({CaseKind::Perturbed, "perturbed-" + std::to_string(s), static_cast<uint64_t>(s), 0});
  if (wants("box")) cases.push_back({CaseKind::Box, "box", 0, 0});
  if (wants("gap")) {
    const auto gaps = split_list(a.gaps);
    if (gaps.empty()) throw InputError("--gaps is empty: give seconds such as 0.5,2");
    for (const auto& g : gaps) {
      const double seconds = parse_numbers(g, 1, "--gaps")[0];
      if (!(seconds > 0) || !std::isfinite(seconds)) throw InputError("--gaps takes positive seconds, got '" + g + "'");
      char name[32];
      std::snprintf(name, sizeof name, "gap+%gs", seconds);
      cases.push_back({CaseKind::Gap, name, 1, seconds});
    }
  }
  return cases;
}

// The box of the box case: the object's pixels in the first frame's label image (YCB-Video), else its
// mesh projected at the first frame's ground truth.
void choose_box(EvalObject& o, int label) {
  const SequenceFrame& first = o.sequence.frames.front();
  const fs::path label_image = label_image_beside(first.depth_path);
  if (!label_image.empty() && label >= 0) {
    if (const auto b = label_box(label_image, label)) {
      o.box = InitHint::box((*b)[0], (*b)[1], (*b)[2], (*b)[3]);
      o.box_source = "label";
      return;
    }
    std::fprintf(stderr, "depthtrack: note: no pixel of '%s' is labelled %d: its box is its mesh projected instead\n",
                 label_image.string().c_str(), label);
  }
  if (!first.ground_truth)
    throw InputError("object '" + o.name + "': the box case needs a label image or ground truth in the first frame");
  o.box = projected_box(o.mesh, o.sequence.camera, *first.ground_truth);
  o.box_source = "projected";
}

Mesh load_mesh(const fs::path& path, double unit_scale) {
  Mesh mesh = Mesh::load(path, unit_scale);
  warn_if_mesh_scale_unusual(mesh, path.string(), unit_scale);
  return mesh;
}

// The objects to evaluate: --mesh with its --object (or the clip's only one), or every object of the clip
// (or of --object) with a mesh <name>.obj in --mesh-dir.
std::vector<EvalObject> eval_objects(const EvalArgs& a, bool with_box) {
  if (a.mesh.empty() == a.mesh_dir.empty())
    throw InputError("give either --mesh FILE (with --object) or --mesh-dir DIR");
  const std::vector<ClipObject> clip = clip_objects(a.sequence);
  std::string present;
  for (const auto& c : clip) present += (present.empty() ? "" : ", ") + (c.name.empty() ? "(unnamed)" : c.name);
  const auto find = [&](const std::string& name) {
    const auto it = std::find_if(clip.begin(), clip.end(), [&](const ClipObject& c) { return c.name == name; });
    if (it == clip.end())
      throw InputError("--object '" + name + "' is not in '" + a.sequence + "'; objects present: " + present);
    return *it;
  };
  std::vector<std::pair<ClipObject, fs::path>> chosen;
  if (!a.mesh.empty()) {
    if (a.objects.size() > 1) throw InputError("--mesh is for one object: give one --object (or use --mesh-dir)");
    if (a.objects.empty() && clip.size() != 1)
      throw InputError("'" + a.sequence + "' has " + std::to_string(clip.size()) + " objects (" + present +
                       "): name the one --mesh shows with --object");
    chosen.emplace_back(a.objects.empty() ? clip.front() : find(a.objects.front()), a.mesh);
  } else {
    std::error_code error;
    if (!fs::is_directory(a.mesh_dir, error)) throw InputError("--mesh-dir '" + a.mesh_dir + "' is not a folder");
    std::vector<ClipObject> wanted;
    for (const auto& name : a.objects) wanted.push_back(find(name));
    if (a.objects.empty()) wanted = clip;
    for (const ClipObject& c : wanted) {
      if (c.name.empty())
        throw InputError("'" + a.sequence +
                         "' does not name its object, so --mesh-dir cannot find its mesh: give --mesh");
      const fs::path path = fs::path(a.mesh_dir) / (c.name + ".obj");
      if (fs::is_regular_file(path, error)) {
        chosen.emplace_back(c, path);
      } else if (!a.objects.empty()) {
        throw InputError("--object '" + c.name + "' has no mesh '" + path.string() + "'");
      } else {
        std::fprintf(stderr, "depthtrack: note: skipping '%s': no mesh '%s'\n", c.name.c_str(), path.string().c_str());
      }
    }
    if (chosen.empty())
      throw InputError("--mesh-dir '" + a.mesh_dir + "' has no <name>.obj for any object of '" + a.sequence + "' (" +
                       present + ")");
  }
  std::vector<EvalObject> objects;
  for (const auto& [c, path] : chosen) {
    EvalObject o;
    o.sequence_name = c.name;
    o.name = c.name.empty() ? path.stem().string() : c.name;
    o.mesh_path = path;
    o.sequence = load_sequence(a.sequence, c.name);
    if (o.sequence.frames.empty()) throw InputError("'" + a.sequence + "' has no frames");
    if (std::none_of(o.sequence.frames.begin(), o.sequence.frames.end(),
                     [](const SequenceFrame& f) { return f.ground_truth.has_value(); }))
      throw InputError("'" + a.sequence + "' has no ground truth for object '" + o.name + "': nothing to evaluate");
    // BOP models are in millimetres by the format's definition.
    const bool bop_units = o.sequence.format == "bop" && a.unit_scale_option->count() == 0;
    o.mesh = load_mesh(path, bop_units ? 0.001 : a.unit_scale);
    o.diameter = mesh_diameter(o.mesh);
    o.tolerance = adds_tolerance(o.diameter.metres);
    if (with_box) choose_box(o, c.label);
    objects.push_back(std::move(o));
  }
  return objects;
}

Pose perturbed_start(const EvalObject& o, uint64_t seed) {
  const auto& truth = o.sequence.frames.front().ground_truth;
  if (!truth) throw InputError("object '" + o.name + "' has no ground truth in the first frame to perturb");
  return perturb_pose(*truth, o.mesh.centre().cast<double>(), kPerturbMetres, kPerturbDegrees, seed);
}

std::vector<TrackedFrame> run_case(const EvalObject& o, const EvalCase& c, const EvalArgs& a,
                                   const TrackerConfig& config, const InitialSpread& spread,
                                   const std::function<void(size_t, const TrackedFrame&)>& on_frame) {
  switch (c.kind) {
    case CaseKind::Perturbed:
      return track_sequence(o.sequence, o.mesh, config, perturbed_start(o, c.seed), spread, on_frame);
    case CaseKind::Box:
      return track_sequence_global(o.sequence, o.mesh, config, o.box, on_frame);
    case CaseKind::Gap: {
      Sequence stalled = o.sequence;  // the same images; only the clock jumps
      for (size_t i = static_cast<size_t>(a.gap_before); i < stalled.frames.size(); ++i)
        stalled.frames[i].timestamp += c.gap;
      return track_sequence(stalled, o.mesh, config, perturbed_start(o, c.seed), spread, on_frame);
    }
  }
  return {};
}

void print_objects(const std::vector<EvalObject>& objects) {
  for (const EvalObject& o : objects) {
    std::printf("%s: mesh %s, diameter %.1f mm (%s), tolerance %.2f mm", o.name.c_str(), o.mesh_path.string().c_str(),
                1000 * o.diameter.metres,
                o.diameter.exact ? "exact, over the convex hull's vertices" : "bounding-box diagonal, an upper bound",
                1000 * o.tolerance);
    if (!o.box_source.empty())
      std::printf(", box %d %d %d %d from the %s", o.box.u0, o.box.v0, o.box.u1, o.box.v1,
                  o.box_source == "label" ? "first frame's label image" : "mesh projected at the first ground truth");
    std::printf("\n");
  }
}

void run_eval(const EvalArgs& a) {
  const std::vector<EvalCase> cases = eval_cases(a);
  const bool with_box =
      std::any_of(cases.begin(), cases.end(), [](const EvalCase& c) { return c.kind == CaseKind::Box; });
  TrackerConfig config = a.tracker.resolve();
  if (a.no_recover) config.recovery.enabled = false;
  const InitialSpread spread = parse_init_spread(a.init_spread);
  std::optional<PlotRunner> plot;
  if (!a.reliability.empty()) {
    if (fs::path(a.reliability).extension() != ".png")
      throw InputError("--reliability '" + a.reliability + "' must name a .png file");
    plot = find_plot_runner("--reliability");
  }
  const std::vector<EvalObject> objects = eval_objects(a, with_box);
  const bool with_gap =
      std::any_of(cases.begin(), cases.end(), [](const EvalCase& c) { return c.kind == CaseKind::Gap; });
  for (const EvalObject& o : objects)
    if (with_gap && (a.gap_before < 1 || static_cast<size_t>(a.gap_before) >= o.sequence.frames.size()))
      throw InputError("--gap-before " + std::to_string(a.gap_before) + " must name a frame after the first: 1 to " +
                       std::to_string(o.sequence.frames.size() - 1) + " for '" + a.sequence + "'");
  // Both outputs are checked before any tracking and replace earlier files together once the run succeeded;
  // without --frames-out the diagram's rows go to a file beside the PNG, removed after drawing.
  StagedOutputs outputs;
  const fs::path frames_path = a.frames_out.empty() ? fs::path() : outputs.add("--frames-out", a.frames_out);
  const fs::path png_path = plot ? outputs.add("--reliability", a.reliability) : fs::path();
  std::optional<EvalFramesCsv> csv;
  if (!a.frames_out.empty())
    csv.emplace(frames_path);
  else if (plot)
    csv.emplace(a.reliability + ".frames.csv");

  print_objects(objects);
  size_t width = 0;
  for (const EvalObject& o : objects) width = std::max(width, o.name.size());
  EvalTable table(width);
  table.print_header();
  std::vector<ConfidenceOutcome> outcomes;
  std::vector<CoverageRow> coverage_rows;
  std::vector<CovarianceCheck> all_checks;
  size_t all_no_region = 0;
  for (const EvalObject& o : objects)
    for (const EvalCase& c : cases) {
      ProgressBar bar(o.name + " " + c.name, static_cast<int>(o.sequence.frames.size()));
      const auto begin = std::chrono::steady_clock::now();
      const auto frames = run_case(o, c, a, config, spread, [&](size_t i, const TrackedFrame& f) {
        char text[48] = "";
        if (!std::isnan(f.adds)) std::snprintf(text, sizeof text, "ADD-S %.1f mm", 1000 * f.adds);
        bar.update(static_cast<int>(i + 1), text);
      });
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
      bar.finish();
      CaseRow row{o.name,
                  c.name,
                  c.kind,
                  {},
                  seconds,
                  o.box_source,
                  frames.empty() ? StepTimings{} : frames.front().estimate.timings};
      const std::optional<size_t> recovery_from =
          c.kind == CaseKind::Gap ? std::optional<size_t>(static_cast<size_t>(a.gap_before) + kRecoveryFrames)
                                  : std::nullopt;
      row.scores = score_case(frames, o.tolerance, recovery_from);
      table.print_row(row);
      std::vector<CovarianceCheck> checks;
      size_t no_region = 0;
      for (const TrackedFrame& f : frames) {
        const std::optional<CovarianceCheck> check =
            f.ground_truth
                ? check_covariance(pose_error_twist(f.estimate.pose, *f.ground_truth, o.mesh.centre().cast<double>()),
                                   f.estimate.covariance)
                : std::nullopt;
        if (check) checks.push_back(*check);
        if (f.ground_truth && !check) ++no_region;
        if (csv) csv->write(o.name, c.name, f, o.tolerance, check);
        if (!std::isnan(f.adds)) outcomes.push_back({f.estimate.confidence, f.adds <= o.tolerance});
      }
      coverage_rows.push_back({o.name, c.name, coverage(checks, no_region)});
      all_checks.insert(all_checks.end(), checks.begin(), checks.end());
      all_no_region += no_region;
    }
  table.print_summary();
  std::printf(
      "conf_wrong: ADD-S > %.0f mm while tracking with confidence >= %.1f; false_lost: lost while within tolerance; "
      "recovered: every frame from %zu after the gap (frame index %d on) within %.0f mm or lost\n",
      1000 * kConfidentWrongAdds, kConfidentAbove, kRecoveryFrames, a.gap_before + static_cast<int>(kRecoveryFrames),
      1000 * kEndsWithin);
  print_reliability(reliability(outcomes));
  coverage_rows.push_back({"all", "", coverage(all_checks, all_no_region)});
  print_coverage(coverage_rows, width);
  if (csv) csv->finish();
  if (plot) {
    const fs::path rows = csv->path();
    try {
      std::printf("%s\n", run_plots(*plot, {"reliability", rows.string(), png_path.string()}).c_str());
    } catch (...) {
      if (a.frames_out.empty()) fs::remove(rows);
      throw;
    }
    if (a.frames_out.empty()) fs::remove(rows);
  }
  outputs.commit();
  if (!a.frames_out.empty()) std::printf("wrote %s\n", a.frames_out.c_str());
  if (plot) std::printf("wrote %s\n", a.reliability.c_str());
}

}  // namespace

void add_eval_command(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  CLI::App* c = app.add_subcommand(
      "eval",
      "Measure the tracker's accuracy and trustworthiness on a clip with ground truth: per object and start "
      "(perturbed ground truth, a 2D box, a stall in the timestamps) a table row of ADD-S, its AUC, status counts, "
      "confident-but-wrong frames and false losses, then a summary and the confidence's reliability");
  c->add_option("--sequence", args->sequence,
                "Sequence folder with ground truth: YCB-Video (gt.json), depthtrack's own (sequence.json) or BOP")
      ->required();
  c->add_option("--mesh-dir", args->mesh_dir,
                "Folder of meshes <name>.obj: every object of the clip that has one is evaluated (e.g. "
                "../shared/data/meshes/ycb)");
  c->add_option("--mesh", args->mesh, "One object's mesh (with --object, unless the clip has one object)");
  c->add_option("--object", args->objects,
                "Evaluate this object (YCB-Video name, BOP obj_id); repeat it to evaluate several (with --mesh-dir)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  args->unit_scale_option = c->add_option("--unit-scale", args->unit_scale,
                                          "Multiply mesh coordinates by this to get metres (default 1; 0.001 for BOP)");
  c->add_option("--cases", args->cases,
                "Comma-separated cases: perturbed (ground truth moved by exactly 1 cm and 5 deg, seeds 1..N), box "
                "(global search in the object's first-frame box: from the label image NNNNNN-label.png where there "
                "is one, else the mesh projected at ground truth), gap (perturbed seed 1 with every timestamp from "
                "--gap-before on shifted by each of --gaps)")
      ->capture_default_str();
  c->add_option("--seeds", args->seeds, "Perturbed starts per object (perturbation seeds 1..N)")->capture_default_str();
  c->add_option("--gaps", args->gaps, "Comma-separated seconds the clock jumps by in the gap cases")
      ->capture_default_str();
  c->add_option("--gap-before", args->gap_before, "Index of the first frame after the jump (frames count from 0)")
      ->capture_default_str();
  c->add_option("--init-spread", args->init_spread,
                "Standard deviation \"METRES DEGREES\" of the initial particle cloud of the perturbed and gap starts")
      ->capture_default_str();
  c->add_flag("--no-recover", args->no_recover, "Do not search for the object again while it is lost");
  c->add_option("--frames-out", args->frames_out,
                "CSV with a row per frame of every case: object,case,frame,timestamp,adds_mm,confidence,status,"
                "within_tolerance,covariance_d2,covariance_dof,within_95,axis_d2_x,axis_d2_y,axis_d2_z,axis_d2_rx,"
                "axis_d2_ry,axis_d2_rz (the error's squared Mahalanobis distance under Estimate::covariance, its "
                "determined axes, whether it lies inside the 95 % region, and each determined axis' error^2 / "
                "variance; written to FILE.partial and renamed at the end)");
  c->add_option("--reliability", args->reliability,
                "Draw the confidence's reliability diagram as this PNG (python3 with matplotlib runs "
                "depthtrack/plots.py on the frames)");
  args->tracker.add_to(*c);
  c->callback([args] { run_eval(*args); });
}

}  // namespace depthtrack::cli
