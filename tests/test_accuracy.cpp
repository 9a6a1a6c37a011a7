// Tracking accuracy of the reference filter on data whose noise is not the model's own:
// a synthetic structured-light handset sequence with a moving occluder, and real YCB-Video depth.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/synth.hpp>
#include <numbers>
#include <vector>

#include "device_support.hpp"
#include "reference/rasterizer.hpp"
#include "support.hpp"

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

RunErrors track_frames(const Mesh& mesh, const SynthConfig& synth, const std::vector<SynthFrame>& frames,
                       OcclusionStorage mode, uint64_t seed, const std::string& backend) {
  TrackerConfig config;  // 200 particles at 80x60: the thesis' CPU operating point
  config.backend = backend;
  config.occlusion_storage = mode;
  config.seed = seed;
  Tracker tracker(mesh, synth.camera, config);
  tracker.initialize(frames.front().ground_truth);
  RunErrors e;
  for (const SynthFrame& f : frames) {
    const Estimate update = tracker.update(f.depth, f.timestamp);
    const Pose& estimate = update.pose;
    e.lost_frames += update.status == TrackStatus::Lost;
    e.min_confidence = std::min(e.min_confidence, update.confidence);
    const double t = translation_error(estimate, f.ground_truth);
    e.mean_t += t / static_cast<double>(frames.size());
    e.max_t = std::max(e.max_t, t);
    e.mean_r += rotation_error(estimate, f.ground_truth) / static_cast<double>(frames.size());
  }
  return e;
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

TEST_CASE("synthetic handset with a 30% moving occluder: 200 particles at 80x60", "[accuracy]") {
  const auto path = test::shared_data("meshes/dbot/handset.obj");
  if (!path) return;
  const Mesh mesh = Mesh::load(*path);
  SynthConfig synth;  // 640x480 structured-light sensor, 30 Hz
  synth.frames = 150;
  synth.occluder_fraction = 0.3;
  const Synthesizer scene(mesh, synth);
  std::vector<SynthFrame> frames;
  double occluded = 0;
  for (int i = 0; i < synth.frames; ++i) {
    frames.push_back(scene.frame(i));
    occluded += frames.back().occluded_fraction / synth.frames;
  }
  REQUIRE(occluded == Approx(0.3).margin(0.02));

  for (const std::string& backend : backends()) {
    std::printf("\nhandset, %d frames, mean occluded %.2f, backend %s     mean mm   max mm   mean deg\n", synth.frames,
                occluded, backend.c_str());
    // Three tracker seeds: the bars hold per run for translation; rotation about the handset's long,
    // nearly round axis is weakly observable at 80x60, so its bar is on the mean over the runs.
    double rotation_over_runs = 0;
    for (uint64_t seed : {1, 2, 3}) {
      const RunErrors e = track_frames(mesh, synth, frames, OcclusionStorage::PerPixelTime, seed, backend);
      std::printf("  occlusion per-pixel-time, seed %llu       %7.2f  %7.2f  %7.2f\n",
                  static_cast<unsigned long long>(seed), 1000 * e.mean_t, 1000 * e.max_t, kDegrees * e.mean_r);
      std::printf("    lowest confidence %.2f, lost in %d frames\n", e.min_confidence, e.lost_frames);
      CHECK(e.mean_t <= 0.005);
      CHECK(e.max_t <= 0.020);
      CHECK(e.lost_frames == 0);  // no false loss: the object is tracked throughout
      rotation_over_runs += e.mean_r / 3;
    }
    const RunErrors off = track_frames(mesh, synth, frames, OcclusionStorage::Off, 1, backend);
    std::printf("  occlusion off, seed 1                  %7.2f  %7.2f  %7.2f\n", 1000 * off.mean_t, 1000 * off.max_t,
                kDegrees * off.mean_r);
    std::printf("  mean rotation error over the three seeds: %.2f deg\n", kDegrees * rotation_over_runs);
    CHECK(kDegrees * rotation_over_runs <= 3.0);
  }
}

TEST_CASE("YCB-Video clip 0000: each object from ground truth perturbed by 1 cm and 5 degrees", "[accuracy]") {
  const auto clip = test::shared_data("sequences/ycbv-0000/gt.json");
  if (!clip) return;
  for (const std::string& backend : backends()) {
    std::printf(
        "\nycbv-0000 at 160x120, 200 particles, %s, last frame:  t mm   r deg  ADD-S mm  fit: estimate / truth mm\n",
        backend.c_str());
    for (const char* object : {"009_gelatin_box", "025_mug", "061_foam_brick"}) {
      const auto mesh_path = test::shared_data(std::string("meshes/ycb/") + object + ".obj");
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
      double min_confidence = 1;
      for (const TrackedFrame& f : frames) {
        CHECK(f.estimate.status == TrackStatus::Tracking);  // no false loss
        min_confidence = std::min(min_confidence, f.estimate.confidence);
      }
      std::printf("  %-16s lowest confidence %.2f\n", object, min_confidence);
      const double adds = AddsMetric(mesh)(last.estimate.pose, *last.ground_truth);
      const DepthImage depth = sequence.load_depth(frames.size() - 1);
      const double fit_estimate = median_depth_residual(mesh, sequence.camera, last.estimate.pose, depth);
      const double fit_truth = median_depth_residual(mesh, sequence.camera, *last.ground_truth, depth);
      std::printf("  %-16s %31.2f %7.2f %9.2f  %6.2f / %.2f\n", object, 1000 * last.translation_error,
                  kDegrees * last.rotation_error, 1000 * adds, 1000 * fit_estimate, 1000 * fit_truth);
      CHECK(adds <= 0.004);
      // Within 5 mm of ground truth; where ground truth itself misses the measured surface by
      // more than the sensor's noise (the foam brick's: ~4 mm median), the estimate must instead
      // explain the depth at least as well as ground truth does.
      if (fit_truth <= 0.0025) {
        CHECK(last.translation_error <= 0.005);
      } else {
        CHECK(fit_estimate <= fit_truth);
        CHECK(last.translation_error <= 0.010);
      }
    }
  }
}
