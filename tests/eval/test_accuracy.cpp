// Tracking accuracy of the reference filter on data whose noise is not the model's own:
// a synthetic structured-light handset sequence with a moving occluder, real YCB-Video depth, and
// ViSP's simulated castle.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/synth.hpp>
#include <numbers>
#include <vector>

#include "core/mesh_symmetry.hpp"
#include "device_support.hpp"
#include "io/visp_simulated_sequence.hpp"
#include "reference/rasterizer.hpp"
#include "support.hpp"
#include "synth_frames.hpp"

using namespace depthtrack;

namespace {
constexpr double kDegrees = 180.0 / std::numbers::pi;

struct RunErrors {
  double mean_t = 0, max_t = 0, mean_r = 0;  // metres, metres, radians
  int lost_frames = 0;                       // frames whose status was lost
  double min_confidence = 1;
};

// The reference filter, and the device filter on the test device when one opens.
std::vector<std::string> backends() {
  std::vector<std::string> names = {"reference"};
  if (test::device_available()) names.push_back(test::device_selector());
  return names;
}

// Tracks frames from start (particles spread by `spread` around it); errors averaged over frames
// first.. (the first ones are the filter converging from a perturbed start).
RunErrors track_frames(const Mesh& mesh, const SynthConfig& synth, const std::vector<SynthFrame>& frames,
                       const TrackerConfig& config, const Pose& start, const InitialSpread& spread = {},
                       size_t first = 0) {
  Tracker tracker(mesh, synth.camera, config);
  tracker.initialize(start, spread);
  RunErrors e;
  const double counted = static_cast<double>(frames.size() - first);
  for (size_t i = 0; i < frames.size(); ++i) {
    const SynthFrame& f = frames[i];
    const Estimate update = tracker.update(f.depth, f.timestamp);
    const Pose& estimate = update.pose;
    e.lost_frames += update.status == TrackStatus::Lost;
    e.min_confidence = std::min(e.min_confidence, update.confidence);
    if (i < first) continue;
    const double t = translation_error(estimate, f.ground_truth);
    e.mean_t += t / counted;
    e.max_t = std::max(e.max_t, t);
    e.mean_r += rotation_error(estimate, f.ground_truth) / counted;
  }
  return e;
}

// 200 particles at 80x60 (the thesis' CPU operating point) on backend.
TrackerConfig operating_point(const std::string& backend, uint64_t seed, bool refine) {
  TrackerConfig config;
  config.backend = backend;
  config.seed = seed;
  config.refine.enabled = refine;
  return config;
}

void print_row(const char* label, const RunErrors& e) {
  std::printf("  %-40s %7.2f  %7.2f  %7.2f\n", label, 1000 * e.mean_t, 1000 * e.max_t, kDegrees * e.mean_r);
}

// Median |sensor depth - rendered depth| over the pixels the pose covers, ignoring gross outliers
// (occluders, background): how well a pose explains the measured surface.
double median_depth_residual(const Mesh& mesh, const Camera& camera, const Pose& pose, const DepthImage& depth) {
  reference::Rasterizer r(mesh, camera, 0.05, 10.0);
  std::vector<float> rendered(static_cast<size_t>(camera.pixel_count()));
  r.render(pose, rendered);
  std::vector<double> residuals;
  for (size_t k = 0; k < rendered.size(); ++k) {
    const float y = depth.data()[k];
    if (rendered[k] > 0 && DepthImage::is_valid(y) && std::abs(y - rendered[k]) < 0.03)
      residuals.push_back(std::abs(y - rendered[k]));
  }
  if (residuals.empty()) return INFINITY;
  std::nth_element(residuals.begin(), residuals.begin() + static_cast<std::ptrdiff_t>(residuals.size() / 2),
                   residuals.end());
  return residuals[residuals.size() / 2];
}
}  // namespace

TEST_CASE("synthetic handset, ideal sensor: refinement reaches sub-millimetre precision", "[accuracy]") {
  const auto path = test::shared_data("meshes/dbot/handset.obj");
  if (!path) return;
  const Mesh mesh = Mesh::load(*path);
  SynthConfig synth;  // 640x480, 30 Hz, exact z-depth, no occluder
  synth.frames = 150;
  synth.sensor.kind = SensorKind::Ideal;
  const std::vector<SynthFrame> frames = test::synthesize(mesh, synth);
  const Eigen::Vector3d centre = mesh.centre().cast<double>();
  const Pose start = perturb_pose(frames.front().ground_truth, centre, 0.01, 5.0, 1);
  const InitialSpread spread{0.01, 5.0 / kDegrees};
  for (const std::string& backend : backends()) {
    std::printf("\nhandset, ideal sensor, from 1 cm / 5 deg off, frames 5..149, %s    mean mm   max mm   mean deg\n",
                backend.c_str());
    const RunErrors refined = track_frames(mesh, synth, frames, operating_point(backend, 1, true), start, spread, 5);
    print_row("refine on", refined);
    const RunErrors off = track_frames(mesh, synth, frames, operating_point(backend, 1, false), start, spread, 5);
    print_row("refine off (the filter alone)", off);
    CHECK(refined.mean_t <= 0.0005);
    CHECK(kDegrees * refined.mean_r <= 0.2);
  }
}

// The worst frame of a run behind the occluder. Where the bar leaves two strips of the handset seen, the
// fit's second stage (refine.fine_noise_scale) has a narrow optimum about 6 mm off that a run may end one
// frame in (docs/peers-icg.md: over eleven seeds, against one stage).
constexpr double kWorstOccludedFrame = 0.0065;

TEST_CASE("synthetic handset with a 30% moving occluder: 200 particles at 80x60", "[accuracy]") {
  const auto path = test::shared_data("meshes/dbot/handset.obj");
  if (!path) return;
  const Mesh mesh = Mesh::load(*path);
  SynthConfig synth;  // 640x480 structured-light sensor, 30 Hz
  synth.frames = 150;
  synth.occluder_fraction = 0.3;
  const std::vector<SynthFrame> frames = test::synthesize(mesh, synth);
  double occluded = 0;
  for (const SynthFrame& f : frames) occluded += f.occluded_fraction / synth.frames;
  REQUIRE(occluded == Approx(0.3).margin(0.02));

  for (const std::string& backend : backends()) {
    std::printf("\nhandset, %d frames, mean occluded %.2f, backend %s     mean mm   max mm   mean deg\n", synth.frames,
                occluded, backend.c_str());
    // Three tracker seeds, each bar per run.
    for (uint64_t seed : {1, 2, 3}) {
      const RunErrors e =
          track_frames(mesh, synth, frames, operating_point(backend, seed, true), frames.front().ground_truth);
      const std::string label = "refine on, per-pixel-time, seed " + std::to_string(seed);
      print_row(label.c_str(), e);
      CHECK(e.mean_t <= 0.0012);
      CHECK(e.max_t <= kWorstOccludedFrame);
      CHECK(kDegrees * e.mean_r <= 1.2);
      std::printf("    lowest confidence %.2f, lost in %d frames\n", e.min_confidence, e.lost_frames);
      CHECK(e.lost_frames == 0);  // no false loss: the object is tracked throughout
    }
    // The runs above keep the occlusion state in the automatic window around the estimate (the
    // default; the handset covers about 18x12 pixels); the same with the whole image's state, the model
    // as MODEL.md writes it: the same bars.
    for (uint64_t seed : {1, 2, 3}) {
      TrackerConfig whole = operating_point(backend, seed, true);
      whole.occlusion_window = OcclusionWindow::whole_image();
      const RunErrors e = track_frames(mesh, synth, frames, whole, frames.front().ground_truth);
      const std::string label = "refine on, whole image's state, seed " + std::to_string(seed);
      print_row(label.c_str(), e);
      CHECK(e.mean_t <= 0.0012);
      CHECK(e.max_t <= kWorstOccludedFrame);
      CHECK(kDegrees * e.mean_r <= 1.2);
      CHECK(e.lost_frames == 0);
    }
    TrackerConfig no_occlusion = operating_point(backend, 1, true);
    no_occlusion.occlusion_storage = OcclusionStorage::Off;
    const RunErrors without_occlusion = track_frames(mesh, synth, frames, no_occlusion, frames.front().ground_truth);
    print_row("refine on, occlusion off, seed 1", without_occlusion);
    // Without the occlusion model the occluder pulls the fit (measured 1.4-1.6 mm mean, 16 mm max):
    // still within the filter-alone bars, and worse than with it.
    CHECK(without_occlusion.mean_t <= 0.005);
    CHECK(without_occlusion.max_t <= 0.020);
    // Today's filter without refinement, for comparison (its bars: 5 mm mean, 20 mm max).
    const RunErrors off =
        track_frames(mesh, synth, frames, operating_point(backend, 1, false), frames.front().ground_truth);
    print_row("refine off, per-pixel-time, seed 1", off);
    CHECK(off.mean_t <= 0.005);
    CHECK(off.max_t <= 0.020);
  }
}

namespace {
// Each object of a YCB-Video clip from its ground truth perturbed by 1 cm and 5 degrees, at 160x120 on each
// backend: no false loss, the last frame within 4 mm ADD-S, and within 5 mm of the ground truth unless the
// ground truth itself misses the measured surface by more than the sensor's noise, where the estimate must
// instead explain the depth at least as well as the ground truth does.
void track_clip_objects(const std::string& clip_name, const std::vector<std::string>& objects) {
  const auto clip = test::shared_data("sequences/" + clip_name + "/gt.json");
  if (!clip) return;
  for (const std::string& backend : backends()) {
    std::printf(
        "\n%s at 160x120, 200 particles, %s, last frame:  t mm   r deg  ADD-S mm  fit: estimate / truth mm"
        "   all frames, mean: t mm  r deg  ADD-S mm\n",
        clip_name.c_str(), backend.c_str());
    for (const std::string& object : objects) {
      const auto mesh_path = test::shared_data("meshes/ycb/" + object + ".obj");
      if (!mesh_path) return;
      const Mesh mesh = Mesh::load(*mesh_path);
      const Sequence sequence = load_sequence(clip->parent_path(), object);
      TrackerConfig config;
      config.backend = backend;
      config.width = 160;
      config.height = 120;
      const Pose& truth0 = *sequence.frames.front().ground_truth;
      const Eigen::Vector3d centre = mesh.centre().cast<double>();
      const Pose start = perturb_pose(truth0, centre, 0.01, 5.0, 1);
      REQUIRE((start.apply(centre) - truth0.apply(centre)).norm() == Approx(0.01));
      REQUIRE(kDegrees * rotation_error(start, truth0) == Approx(5.0));
      const auto frames = track_sequence(sequence, mesh, config, start, InitialSpread{0.01, 5.0 / kDegrees});
      const TrackedFrame& last = frames.back();
      double min_confidence = 1, mean_t = 0, mean_r = 0, mean_adds = 0;
      for (const TrackedFrame& f : frames) {
        CHECK(f.estimate.status == TrackStatus::Tracking);  // no false loss
        min_confidence = std::min(min_confidence, f.estimate.confidence);
        mean_t += f.translation_error / static_cast<double>(frames.size());
        mean_r += f.rotation_error / static_cast<double>(frames.size());
        mean_adds += f.adds / static_cast<double>(frames.size());
      }
      std::printf("  %-19s lowest confidence %.2f\n", object.c_str(), min_confidence);
      const double adds = AddsMetric(mesh)(last.estimate.pose, *last.ground_truth);
      const DepthImage depth = sequence.load_depth(frames.size() - 1);
      const double fit_estimate = median_depth_residual(mesh, sequence.camera, last.estimate.pose, depth);
      const double fit_truth = median_depth_residual(mesh, sequence.camera, *last.ground_truth, depth);
      std::printf("  %-19s %28.2f %7.2f %9.2f  %6.2f / %.2f %26.2f %6.2f %9.2f\n", object.c_str(),
                  1000 * last.translation_error, kDegrees * last.rotation_error, 1000 * adds, 1000 * fit_estimate,
                  1000 * fit_truth, 1000 * mean_t, kDegrees * mean_r, 1000 * mean_adds);
      CHECK(adds <= 0.004);
      if (fit_truth <= 0.0025) {
        CHECK(last.translation_error <= 0.005);
      } else {
        CHECK(fit_estimate <= fit_truth);
        CHECK(last.translation_error <= 0.010);
      }
    }
  }
}
}  // namespace

TEST_CASE("YCB-Video clip 0000: each object from ground truth perturbed by 1 cm and 5 degrees", "[accuracy]") {
  track_clip_objects("ycbv-0000", {"009_gelatin_box", "025_mug", "061_foam_brick"});
}

TEST_CASE("YCB-Video clip 0049: each object from ground truth perturbed by 1 cm and 5 degrees", "[accuracy]") {
  track_clip_objects("ycbv-0049", {"004_sugar_box", "007_tuna_fish_can", "010_potted_meat_can", "024_bowl"});
}

// The tuna fish can and the bowl are symmetric about an axis (their meshes to the last percent), so no
// depth tells their turn about it: the fit's estimate of that turn wandered 3-8 degrees a frame (20 and 12
// degrees mean rotation error over three starts at 80x60), spinning the reported frame at random. The
// reported turn is held where the depth cannot tell it (tracker/held_turn.hpp): the frame keeps the turn it
// started with (5 degrees off at most), the rest of the pose and ADD-S as estimated.
TEST_CASE("YCB-Video clip 0049: a can's and a bowl's reported frames do not spin about their axes", "[accuracy]") {
  const auto clip = test::shared_data("sequences/ycbv-0049/gt.json");
  if (!clip) return;
  std::printf(
      "\nycbv-0049 at 80x60, 200 particles, reference: turn about the axis a frame (rms deg), rotation error "
      "(mean / max deg), mean ADD-S mm\n");
  for (const char* object : {"007_tuna_fish_can", "024_bowl"}) {
    const auto mesh_path = test::shared_data(std::string("meshes/ycb/") + object + ".obj");
    if (!mesh_path) return;
    const Mesh mesh = Mesh::load(*mesh_path);
    const auto axis = symmetry_axis(mesh);
    REQUIRE(axis);
    const Sequence sequence = load_sequence(clip->parent_path(), object);
    TrackerConfig config;
    config.backend = "reference";
    const Pose& truth0 = *sequence.frames.front().ground_truth;
    const Pose start = perturb_pose(truth0, mesh.centre().cast<double>(), 0.01, 5.0, 1);
    const auto frames = track_sequence(sequence, mesh, config, start, InitialSpread{0.01, 5.0 / kDegrees});
    double turn_squares = 0, mean_r = 0, max_r = 0, mean_adds = 0;
    for (size_t i = 0; i < frames.size(); ++i) {
      const Pose& pose = frames[i].estimate.pose;
      if (i > 0) {
        // The turn about the object's axis from the last frame's report to this one's.
        const Eigen::Quaterniond relative = frames[i - 1].estimate.pose.rotation.conjugate() * pose.rotation;
        const double turn = 2 * std::atan2(relative.vec().dot(axis->direction.normalized()), relative.w());
        turn_squares += turn * turn / static_cast<double>(frames.size() - 1);
      }
      CHECK(frames[i].estimate.status == TrackStatus::Tracking);
      mean_r += frames[i].rotation_error / static_cast<double>(frames.size());
      max_r = std::max(max_r, frames[i].rotation_error);
      mean_adds += frames[i].adds / static_cast<double>(frames.size());
    }
    std::printf("  %-18s %6.2f  %6.2f / %6.2f  %6.2f\n", object, kDegrees * std::sqrt(turn_squares), kDegrees * mean_r,
                kDegrees * max_r, 1000 * mean_adds);
    CHECK(kDegrees * std::sqrt(turn_squares) <= 0.5);
    CHECK(kDegrees * max_r <= 8.0);
    CHECK(mean_adds <= 0.0025);
  }
}

// ViSP's simulated castle (noise-free depth, exact ground truth; 40 frames, the camera circling it):
// the sequence the first precision figures came from (then 300 particles: 3.6 mm / 1.5 deg).
// ViSP's own dense-depth fitter on these frames: 0.84-1.01 mm / 0.37-0.48 deg mean, at 160x120 to
// 640x480 (scripts/compare-peers.sh; docs/performance.md).
TEST_CASE("ViSP's simulated castle from ground truth perturbed by 1 cm and 5 degrees: 200 particles at 160x120",
          "[accuracy][visp]") {
  const auto castle = test::shared_data("sequences/visp-castle-simu");
  if (!castle) return;
  io::VispSimulatedImport castle_camera;
  castle_camera.depth_from_colour = Pose(Eigen::Vector3d(-0.05, 0, 0), Eigen::Quaterniond::Identity());
  const auto folder = test::temp_dir("accuracy_castle");
  const Sequence sequence = io::import_visp_simulated_sequence(*castle, folder, castle_camera);
  const Mesh mesh = Mesh::load(*castle / "Models" / "DERIVED_chateau_plus_cube_triangulated.obj");
  const Pose& truth0 = *sequence.frames.front().ground_truth;
  const Pose start = perturb_pose(truth0, mesh.centre().cast<double>(), 0.01, 5.0, 1);
  for (const std::string& backend : backends()) {
    TrackerConfig config;
    config.backend = backend;
    config.width = 160;
    config.height = 120;
    const auto frames = track_sequence(sequence, mesh, config, start, InitialSpread{0.01, 5.0 / kDegrees});
    RunErrors e;
    const size_t first = 5;  // the start worked off
    const double counted = static_cast<double>(frames.size() - first);
    for (size_t i = first; i < frames.size(); ++i) {
      e.mean_t += frames[i].translation_error / counted;
      e.mean_r += frames[i].rotation_error / counted;
      e.max_t = std::max(e.max_t, frames[i].translation_error);
      e.lost_frames += frames[i].estimate.status == TrackStatus::Lost;
    }
    std::printf(
        "\nvisp-castle, 40 frames at 160x120, 200 particles, %s, frames 5..39: %.2f mm mean, %.2f mm max, "
        "%.2f deg mean\n",
        backend.c_str(), 1000 * e.mean_t, 1000 * e.max_t, kDegrees * e.mean_r);
    CHECK(e.lost_frames == 0);
    CHECK(e.mean_t <= 0.0008);
    CHECK(e.max_t <= 0.002);
    CHECK(kDegrees * e.mean_r <= 0.4);
  }
}
