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
#include "search/visible_box.hpp"
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

// The built-in object behind a 30 % occluder, one frame, at the working resolution 80x60.
struct OccludedFrame {
  Mesh mesh = builtin_demo_mesh();
  SynthFrame frame;
  Camera working;
  DepthImage depth;
  OccludedFrame() {
    SynthConfig synth;
    synth.frames = 1;
    synth.occluder_fraction = 0.3;
    frame = Synthesizer(mesh, synth).frame(0);
    working = synth.camera.decimated(8);
    depth = frame.depth.decimated(8);
  }
};
}  // namespace

TEST_CASE("device pose scores equal the reference's", "[global][device]") {
  if (!test::device_available()) return;
  const OccludedFrame scene;
  const Mesh& mesh = scene.mesh;
  const SynthFrame& frame = scene.frame;
  const Camera& working = scene.working;
  const DepthImage& depth = scene.depth;
  for (const OcclusionStorage mode : {OcclusionStorage::PerPixelTime, OcclusionStorage::Off}) {
    TrackerConfig config;
    config.occlusion_storage = mode;
    reference::ReferenceFilter reference(mesh, working, config);
    DeviceFilter device(compute::open_device(test::device_selector()), mesh, working, config);
    // More poses than a CPU device's batch, so that a partly filled batch is checked too.
    const std::vector<Pose> poses = test_poses(frame.ground_truth, mesh.centre().cast<double>(), 700);
    const std::vector<double> expected = reference.score_poses(poses, depth, config.observation);
    const std::vector<double> got = device.score_poses(poses, depth, config.observation);
    REQUIRE(got.size() == poses.size());
    const auto& scale = reference.last_score_magnitudes();
    double worst = 0;
    for (size_t i = 0; i < poses.size(); ++i) {
      // Relative to the sum of |per-pixel term|, as tests/filter/test_device_filter.cpp compares weigh.
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

// The box agreement's device side: each pose's visible box from the coarse scorer's vertices on the device,
// against search::visible_box on the host (double), on a scene where an occluder hides part of the object.
TEST_CASE("device visible boxes equal the host's", "[global][device][box]") {
  if (!test::device_available()) return;
  const OccludedFrame s;
  TrackerConfig config;
  DeviceFilter device(compute::open_device(test::device_selector()), s.mesh, s.working, config);
  const std::unique_ptr<PoseScorer> scorer = device.make_pose_scorer(s.mesh);
  const std::vector<Pose> poses = test_poses(s.frame.ground_truth, s.mesh.centre().cast<double>(), 700);
  const double sigmas = config.loss.pixel_sigmas;
  const std::vector<float> got = scorer->visible_boxes(poses, s.depth, config.observation, sigmas);
  REQUIRE(got.size() == 4 * poses.size());
  std::vector<Eigen::Vector3d> vertices;
  for (const auto& v : s.mesh.vertices) vertices.push_back(v.cast<double>());
  size_t differ = 0, empty = 0, partly_hidden = 0;
  double worst = 0;
  for (size_t i = 0; i < poses.size(); ++i) {
    const search::ImageBox want =
        search::visible_box(vertices, poses[i], s.working, s.depth, config.observation, sigmas);
    const search::ImageBox all = search::visible_box(
        vertices, poses[i], s.working, DepthImage(s.working.width, s.working.height), config.observation, sigmas);
    const float* b = got.data() + 4 * i;
    const search::ImageBox have{b[0], b[1], b[2], b[3]};
    CHECK(have.empty() == want.empty());
    if (want.empty()) {
      ++empty;
      continue;
    }
    partly_hidden += want.area() < all.area();
    const double d = std::max({std::abs(have.u0 - want.u0), std::abs(have.v0 - want.v0), std::abs(have.u1 - want.u1),
                               std::abs(have.v1 - want.v1)});
    worst = std::max(worst, d);
    differ += d > 1e-3;
  }
  std::printf("visible boxes, %zu poses (%zu partly hidden, %zu empty): %zu differ by over 1e-3 px, worst %.2g px\n",
              poses.size(), partly_hidden, empty, differ, worst);
  // float against double: a vertex within rounding of a pixel's edge or of the band may fall the other way.
  CHECK(differ <= poses.size() / 100);
  CHECK(partly_hidden > 50);  // the occluder hides parts: the depth test is exercised
  CHECK(empty >= 1);          // the pose behind the camera
}

namespace {
struct YcbObject {
  std::string name;
  int label = 0;  // cls_index: the object's id in the label images
};

std::vector<YcbObject> ycb_objects(const std::filesystem::path& gt) {
  std::ifstream in(gt);
  const auto json = nlohmann::json::parse(in);
  std::vector<YcbObject> out;
  for (const auto& o : json["frames"][0]["objects"]) out.push_back({o["name"], o["cls_index"]});
  return out;
}
}  // namespace

TEST_CASE("YCB-Video clip 0000: each object found from its 2D box in the first frame, and from nothing",
          "[global][accuracy]") {
  const auto clip = test::shared_data("sequences/ycbv-0000/gt.json");
  if (!clip) return;
  // Without a hint the search takes minutes on CI's CPU (the reference, three objects: 14 min on the
  // loaded 2-core machine), so those rows are opt-in; each must still end within 10 mm ADD-S. The
  // reference by default; DEPTHTRACK_TEST_GLOBAL_BACKEND names another (e.g. cuda on the GPU machine).
  const bool no_hint = std::getenv("DEPTHTRACK_TEST_GLOBAL_NO_HINT") != nullptr;
  const char* backend_env = std::getenv("DEPTHTRACK_TEST_GLOBAL_BACKEND");
  const std::string backend = backend_env ? backend_env : "reference";
  std::printf("\nycbv-0000 at 80x60, 200 particles, %-10s start    search s   poses  last: t mm   r deg  ADD-S mm\n",
              backend.c_str());
  for (const YcbObject& object : ycb_objects(*clip)) {
    const auto mesh_path = test::shared_data("meshes/ycb/" + object.name + ".obj");
    if (!mesh_path) return;
    const Mesh mesh = Mesh::load(*mesh_path);
    const AddsMetric adds(mesh);
    const Sequence sequence = load_sequence(clip->parent_path(), object.name);
    const auto box = test::label_box(clip->parent_path() / "000001-label.png", object.label);
    REQUIRE(box);
    std::vector<std::pair<std::string, InitHint>> starts = {
        {"box", InitHint::box((*box)[0], (*box)[1], (*box)[2], (*box)[3])}};
    if (no_hint) starts.push_back({"none", InitHint::anywhere()});
    for (const auto& [start, hint] : starts) {
      TrackerConfig config;
      config.backend = backend;
      const auto frames = track_sequence_global(sequence, mesh, config, hint);
      const TrackedFrame& last = frames.back();
      const double last_adds = adds(last.estimate.pose, *last.ground_truth);
      std::printf("  %-16s %26s %9.2f %9zu %10.2f %7.2f %9.2f\n", object.name.c_str(), start.c_str(),
                  frames.front().estimate.timings.search_ms / 1000, frames.front().estimate.search_poses,
                  1000 * last.translation_error, kDegrees * last.rotation_error, 1000 * last_adds);
      CHECK(last_adds <= 0.010);
      for (const TrackedFrame& f : frames) CHECK(f.estimate.status == TrackStatus::Tracking);
    }
  }
}

// In ycbv-0049's tuna fish can's box the likelihood prefers poses sunk into the surfaces around the can,
// and the grid's nearest candidates lie 15-20 mm nearer the camera than it: it ended 12.5 mm off
// (tolerance 9 mm) until the box's candidates were fitted from deeper starts too, kept by the evidence
// (TrackSupervisor::fit_confident) and, where it supports none, searched for again region by region. In the
// bowl's box the best-scoring poses lie sunk behind its neighbours (their pixels taken for occluded): it ended
// 50 mm off, reported lost, until poses whose visible pixels' box disagrees with the box were ranked below
// those that agree (TrackSupervisor::box_agreement). Neither may be reported tracking while off.
TEST_CASE("YCB-Video clip 0049: the tuna fish can and the bowl found from their 2D boxes", "[global][accuracy]") {
  const auto clip = test::shared_data("sequences/ycbv-0049/gt.json");
  if (!clip) return;
  const char* backend_env = std::getenv("DEPTHTRACK_TEST_GLOBAL_BACKEND");
  for (const YcbObject& object : ycb_objects(*clip)) {
    if (object.name != "007_tuna_fish_can" && object.name != "024_bowl") continue;
    const auto mesh_path = test::shared_data("meshes/ycb/" + object.name + ".obj");
    if (!mesh_path) return;
    const Mesh mesh = Mesh::load(*mesh_path);
    const AddsMetric adds(mesh);
    const Sequence sequence = load_sequence(clip->parent_path(), object.name);
    const auto box = test::label_box(clip->parent_path() / "000001-label.png", object.label);
    REQUIRE(box);
    TrackerConfig config;
    config.backend = backend_env ? backend_env : "reference";
    config.recovery.enabled = false;  // the start alone
    const auto frames =
        track_sequence_global(sequence, mesh, config, InitHint::box((*box)[0], (*box)[1], (*box)[2], (*box)[3]));
    const double last_adds = adds(frames.back().estimate.pose, *frames.back().ground_truth);
    std::printf("ycbv-0049 %s from its box: last frame %.1f mm ADD-S\n", object.name.c_str(), 1000 * last_adds);
    if (object.name == "007_tuna_fish_can") CHECK(last_adds <= 0.1 * 0.0898);  // a tenth of its diameter
    if (object.name == "024_bowl") CHECK(last_adds <= 0.010);
    for (const TrackedFrame& f : frames)
      if (f.estimate.status == TrackStatus::Tracking) CHECK(adds(f.estimate.pose, *f.ground_truth) <= 0.020);
  }
}

// The grid's centres lie behind measured points along their rays; with the bar across the
// handset's middle (frame 0) or the handset tilted in depth (frame 30) none came near its centre and
// the box search landed 163 and 108 mm off (search::box_centre_points).
TEST_CASE("synthetic handset behind a bar found from its box", "[global][accuracy]") {
  const auto handset = test::shared_data("meshes/dbot/handset.obj");
  if (!handset) return;
  const Mesh mesh = Mesh::load(*handset);
  SynthConfig synth;
  synth.frames = 31;
  synth.occluder_fraction = 0.3;
  const Synthesizer scene(mesh, synth);
  for (const int i : {0, 30}) {
    const SynthFrame f = scene.frame(i);
    TrackerConfig config;  // the reference at 80x60
    Tracker tracker(mesh, synth.camera, config);
    const Estimate e =
        tracker.initialize_global(f.depth, f.timestamp, projected_box(mesh, synth.camera, f.ground_truth));
    const double mm = 1000 * translation_error(e.pose, f.ground_truth),
                 deg = kDegrees * rotation_error(e.pose, f.ground_truth);
    std::printf("handset frame %d from its box: %.1f mm, %.1f deg, search %.0f ms\n", i, mm, deg, e.timings.search_ms);
    CHECK(mm <= 10);
    CHECK(deg <= 5);
  }
}

TEST_CASE("global initialization refuses a bad box with a reason", "[global][errors]") {
  const Mesh mesh = builtin_demo_mesh();
  SynthConfig synth;
  synth.camera = Camera::make(160, 120, 131.25, 131.25, 79.875, 59.875);
  synth.frames = 1;
  const SynthFrame frame = Synthesizer(mesh, synth).frame(0);
  // A hole of missing depth in the top-left corner.
  std::vector<float> metres = frame.depth.data();
  for (int v = 0; v < 20; ++v)
    for (int u = 0; u < 30; ++u) metres[static_cast<size_t>(v * 160 + u)] = NAN;
  const DepthImage holed = DepthImage::from_metres(160, 120, metres);
  const DepthImage wall = DepthImage::from_metres(160, 120, std::vector<float>(160 * 120, 1.5f));
  TrackerConfig config;
  Tracker tracker(mesh, synth.camera, config);
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(tracker.initialize_global(holed, 0.0, InitHint::box(50, 40, 20, 60)), Contains("is empty"));
  CHECK_THROWS_WITH(tracker.initialize_global(holed, 0.0, InitHint::box(100, 50, 160, 90)),
                    Contains("is not inside the 160x120 image"));
  CHECK_THROWS_WITH(tracker.initialize_global(holed, 0.0, InitHint::box(-1, 0, 10, 10)), Contains("is not inside"));
  CHECK_THROWS_WITH(tracker.initialize_global(holed, 0.0, InitHint::box(2, 3, 25, 15)),
                    Contains("holds no valid depth"));
  CHECK_THROWS_WITH(tracker.initialize_global(holed, 0.0, InitHint::near_point({0, 0, -1})),
                    Contains("in front of the camera"));
  CHECK_THROWS_WITH(tracker.initialize_global(wall, 0.0), Contains("nothing in the frame stands out"));
  // update() before any initialization is still refused.
  CHECK_THROWS_WITH(tracker.update(holed, 0.0), Contains("before initialize"));
  // A point on the object finds it.
  const Estimate e = tracker.initialize_global(
      frame.depth, 0.0, InitHint::near_point(frame.ground_truth.apply(mesh.centre().cast<double>())));
  CHECK(translation_error(e.pose, frame.ground_truth) <= 0.02);
  CHECK(e.timings.search_ms > 0);
  CHECK(e.search_poses > 0);
}
