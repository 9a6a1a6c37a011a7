// The Tracker on hostile but valid input: far readings, sensor dropouts, sequences
// without any data. Each gives a finite estimate or a clear error, never a NaN row.
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/sequence.hpp>
#include <depthtrack/tracker.hpp>

#include "device_support.hpp"
#include "reference/reference_filter.hpp"
#include "scene.hpp"
#include "support.hpp"

using namespace depthtrack;

namespace {

const Camera sensor = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
const Pose truth({0.0, 0.0, 0.8}, Eigen::Quaterniond::Identity());

bool finite(const Estimate& e) {
  return e.pose.translation.allFinite() && e.pose.rotation.coeffs().allFinite() &&
         std::isfinite(e.effective_sample_size);
}

// Three frames of the scene, the middle one with pixel (40, 30), on the object, set to `middle_pixel`.
std::vector<Estimate> track_three(const std::string& backend, float middle_pixel) {
  TrackerConfig config;
  config.backend = backend;
  config.particles = 50;
  Tracker tracker(builtin_demo_mesh(), sensor, config);
  tracker.initialize(truth);
  const DepthImage scene = test::render_scene(builtin_demo_mesh(), sensor, truth);
  REQUIRE(scene.at(40, 30) < 1.0f);  // the object, not the wall
  DepthImage odd = scene;
  odd.at(40, 30) = middle_pixel;
  return {tracker.update(scene, 0.0), tracker.update(odd, 1.0 / 30), tracker.update(scene, 2.0 / 30)};
}

}  // namespace

TEST_CASE("a reading far beyond max_depth on the object counts as missing, and the pose stays finite",
          "[tracker][robustness]") {
  // 300 m overflowed exp in the observation model (the frame's pose was NaN); beyond max_depth the
  // model has no density, so the pixel is treated as missing: exactly as if it were NaN.
  std::vector<std::string> backends = {"reference"};
  if (test::device_available()) backends.push_back(test::device_selector());
  for (const std::string& backend : backends) {
    INFO(backend);
    const auto far = track_three(backend, 300.0f), missing = track_three(backend, NAN);
    for (size_t i = 0; i < far.size(); ++i) {
      REQUIRE(finite(far[i]));
      CHECK(far[i].pose.translation == missing[i].pose.translation);
      CHECK(far[i].pose.rotation.coeffs() == missing[i].pose.rotation.coeffs());
      // Counted as missing, not as a dropout: the frame keeps its data and its status is the NaN
      // frame's. (Whether 50 particles' first frames are trusted is the confidence's business.)
      CHECK(far[i].status == missing[i].status);
      CHECK(far[i].status != TrackStatus::NoData);
    }
  }
}

TEST_CASE("a frame without any valid pixel is a dropout: the filter predicts, the status says no-data",
          "[tracker][robustness]") {
  TrackerConfig config;
  config.particles = 50;
  Tracker tracker(builtin_demo_mesh(), sensor, config);
  tracker.initialize(truth);
  const DepthImage scene = test::render_scene(builtin_demo_mesh(), sensor, truth);
  CHECK(tracker.update(scene, 0.0).status != TrackStatus::NoData);
  const Estimate dropout = tracker.update(DepthImage(80, 60), 1.0 / 30);
  CHECK(dropout.status == TrackStatus::NoData);
  CHECK(std::string(to_string(dropout.status)) == "no-data");
  CHECK(finite(dropout));
  CHECK_FALSE(dropout.resampled);
  // Readings beyond max_depth only: a dropout too.
  DepthImage far(80, 60);
  for (int v = 0; v < 60; ++v)
    for (int u = 0; u < 80; ++u) far.at(u, v) = 7.0f;
  CHECK(tracker.update(far, 2.0 / 30).status == TrackStatus::NoData);
  const Estimate after = tracker.update(scene, 3.0 / 30);
  CHECK(after.status != TrackStatus::NoData);
  CHECK((after.pose.translation - truth.translation).norm() < 0.02);
}

TEST_CASE("a dropout leaves the weights and the particles' ancestry alone in the reference filter",
          "[tracker][robustness]") {
  TrackerConfig config;
  config.particles = 40;
  config.resample_kl_threshold = 1e9;  // never resample: the weights carry over between frames
  const Camera camera = sensor;
  reference::ReferenceFilter filter(builtin_demo_mesh(), camera, config);
  filter.initialize(truth, InitialSpread{});
  filter.update(test::render_scene(builtin_demo_mesh(), camera, truth), 0.0);
  const std::vector<double> weights = filter.log_weights();
  const auto before = filter.particles();
  const Estimate e = filter.update(DepthImage(80, 60), 1.0 / 30);
  CHECK(filter.log_weights() == weights);
  CHECK_FALSE(e.resampled);
  for (size_t i = 0; i < before.size(); ++i) {
    CHECK(filter.last_parents()[i] == static_cast<int>(i));
    CHECK(filter.particles()[i].pose.translation != before[i].pose.translation);  // propagated
  }
}

TEST_CASE("a sequence in which no frame has a valid pixel is an error", "[tracker][robustness]") {
  const auto dir = test::temp_dir("no_data_sequence");
  Sequence s;
  s.format = "depthtrack";
  s.camera = sensor;
  for (int i = 0; i < 3; ++i) {
    SequenceFrame f;
    f.name = "00000" + std::to_string(i);
    f.timestamp = i / 30.0;
    f.depth_path = dir / (f.name + ".png");
    DepthImage(80, 60).save_png(f.depth_path, 0.001);
    s.frames.push_back(f);
  }
  CHECK_THROWS_WITH(track_sequence(s, builtin_demo_mesh(), TrackerConfig{}, truth, InitialSpread{}),
                    Catch::Contains("no frame of the sequence has a valid depth pixel"));
}
