// Global initialization: batch pose scoring on every backend against the reference, and the
// tracker started from no pose on the YCB-Video clip (from each object's 2D box, and from nothing).
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/synth.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "device_support.hpp"
#include "filter/device_filter.hpp"
#include "label_box.hpp"
#include "reference/reference_filter.hpp"
#include "support.hpp"

using namespace depthtrack;

namespace {
constexpr double kDegrees = 180.0 / std::numbers::pi;

// Poses around and far from the object's true pose: a spread of good, bad and off-image scores.
std::vector<Pose> test_poses(const Pose& truth, const Eigen::Vector3d& centre, size_t n) {
  std::vector<Pose> poses;
  for (size_t i = 0; i < n; ++i) {
    const double metres = 0.002 * static_cast<double>(i % 20), degrees = 3.0 * static_cast<double>(i % 13);
    poses.push_back(perturb_pose(truth, centre, metres, degrees, 100 + i));
  }
  poses.push_back(Pose({0, 0, -1}, Eigen::Quaterniond::Identity()));  // behind the camera: nothing drawn
  return poses;
}
}  // namespace

TEST_CASE("device pose scores equal the reference's", "[global][device]") {
  if (!test::device_available()) return;
  const Mesh mesh = builtin_demo_mesh();
  SynthConfig synth;
  synth.frames = 1;
  synth.occluder_fraction = 0.3;
  const SynthFrame frame = Synthesizer(mesh, synth).frame(0);
  const Camera working = synth.camera.decimated(8);
  const DepthImage depth = frame.depth.decimated(8);
  for (const OcclusionStorage mode : {OcclusionStorage::PerPixelTime, OcclusionStorage::Off}) {
    TrackerConfig config;
    config.occlusion_storage = mode;
    reference::ReferenceFilter reference(mesh, working, config);
    DeviceFilter device(compute::open_device(test::device_selector()), mesh, working, config);
    // More poses than a CPU device's batch, so that a partly filled batch is checked too.
    const std::vector<Pose> poses = test_poses(frame.ground_truth, mesh.centre().cast<double>(), 700);
    const std::vector<double> expected = reference.score_poses(poses, depth);
    const std::vector<double> got = device.score_poses(poses, depth);
    REQUIRE(got.size() == poses.size());
    const auto& scale = reference.last_score_magnitudes();
    double worst = 0;
    for (size_t i = 0; i < poses.size(); ++i) {
      // Relative to the sum of |per-pixel term|, as tests/test_device_filter.cpp compares weigh.
      const double relative = std::abs(got[i] - expected[i]) / std::max(1.0, scale[i]);
      worst = std::max(worst, relative);
      CHECK(relative <= 1e-4);
    }
    std::printf("pose scores, %s, %zu poses: worst relative difference %.2g\n", to_string(mode), poses.size(), worst);
    CHECK(expected.back() == 0.0);  // the pose behind the camera covers nothing
    // The true pose beats the far ones: the scores mean something.
    CHECK(expected.front() > *std::min_element(expected.begin(), expected.end()) + 100);
  }
}
