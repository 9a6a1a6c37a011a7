// The search's host work on threads: every fit, silhouette and item the same as the sequential loop's,
// whatever the thread count.
#include <atomic>
#include <catch2/catch.hpp>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/tracker.hpp>
#include <vector>

#include "reference/pose_refiner.hpp"
#include "synth_frames.hpp"
#include "tracker/search_workers.hpp"

using namespace depthtrack;

namespace {
bool same_pose(const Pose& a, const Pose& b) {
  return a.translation == b.translation && a.rotation.coeffs() == b.rotation.coeffs();
}
}  // namespace

TEST_CASE("the search's fits and silhouettes on threads equal the sequential ones, bit for bit", "[search]") {
  const Mesh mesh = builtin_demo_mesh();
  const SynthConfig synth = test::small_scene(1);
  const SynthFrame frame = test::synthesize(mesh, synth).front();
  TrackerConfig config;
  TrackerConfig fit = config;
  fit.refine.iterations = 16;
  // Starts a few millimetres and degrees around the truth, and one far off.
  std::vector<Pose> starts;
  for (int i = 0; i < 7; ++i)
    starts.push_back(perturb_pose(frame.ground_truth, mesh.centre().cast<double>(), 0.004 * (1 + i % 3), 3.0, i + 1));
  starts.push_back(perturb_pose(frame.ground_truth, mesh.centre().cast<double>(), 0.05, 30.0, 9));
  const std::vector<double> fresh(static_cast<size_t>(synth.camera.pixel_count()), 0.1);

  // The independent expectation: one refiner and one rasterizer, in order.
  const reference::PoseRefiner refiner(mesh, synth.camera, fit);
  const reference::Rasterizer rasterizer(mesh, synth.camera, config.near_plane, config.observation.max_depth);
  std::vector<float> scratch(static_cast<size_t>(synth.camera.pixel_count()));
  for (int threads : {1, 3}) {
    INFO(threads << " threads");
    SearchWorkers workers(mesh, synth.camera, config, fit, threads);
    const std::vector<Pose> fitted = workers.fit(starts, frame.depth, fresh);
    const std::vector<SilhouetteShares> shares = workers.shares(fitted, frame.depth);
    REQUIRE(fitted.size() == starts.size());
    REQUIRE(shares.size() == starts.size());
    for (size_t i = 0; i < starts.size(); ++i) {
      CHECK(same_pose(fitted[i], refiner.refine(starts[i], frame.depth, fresh).pose));
      const SilhouetteShares s =
          silhouette_shares(rasterizer, config.observation, config.loss.pixel_sigmas, fitted[i], frame.depth, scratch);
      CHECK(shares[i].pixels == s.pixels);
      CHECK(shares[i].visible == s.visible);
      CHECK(shares[i].separated == s.separated);
    }
    // The near starts end near the truth: the fits ran.
    CHECK((fitted[0].translation - frame.ground_truth.translation).norm() < 0.004);
    // each() calls every item once.
    std::vector<std::atomic<int>> calls(1000);
    workers.each(calls.size(), [&](size_t i) { ++calls[i]; });
    for (const auto& c : calls) CHECK(c == 1);
  }
}

TEST_CASE("the search's host threads follow the backend", "[search]") {
  TrackerConfig config;
  config.backend = "reference";
  CHECK(search_threads(config) == 1);
  config.backend = "cpu:3";
  CHECK(search_threads(config) == 3);
  config.backend = "cpu";
  CHECK(search_threads(config) == hardware_threads());
}
