// The cpu backend: the reference filter's per-particle loops on a thread pool, equal to the sequential
// reference bit for bit.
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <depthtrack/error.hpp>
#include <depthtrack/synth.hpp>
#include <depthtrack/tracker.hpp>
#include <functional>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/thread_pool.hpp"
#include "model/filter_backend.hpp"
#include "reference/pose_mean.hpp"
#include "reference/reference_filter.hpp"
#include "synth_frames.hpp"
#include "tracker/make_filter_backend.hpp"

using namespace depthtrack;
using Catch::Matchers::Contains;

TEST_CASE("a thread pool runs every task of a batch exactly once and rethrows a task's exception", "[cpu]") {
  for (const int threads : {1, 3}) {
    ThreadPool pool(threads);
    CHECK(pool.size() == threads);
    for (const size_t tasks : {size_t{1}, size_t{2}, size_t{7}, size_t{100}}) {
      std::vector<std::atomic<int>> runs(tasks);
      std::vector<std::atomic<int>> busy(static_cast<size_t>(threads));
      std::atomic<bool> shared_thread{false};
      pool.run(tasks, [&](size_t t, int thread) {
        if (thread < 0 || thread >= threads || busy[static_cast<size_t>(thread)].fetch_add(1) != 0)
          shared_thread = true;
        runs[t].fetch_add(1);
        if (thread >= 0 && thread < threads) busy[static_cast<size_t>(thread)].fetch_sub(1);
      });
      CHECK_FALSE(shared_thread.load());  // no two tasks at once on one thread index
      for (size_t t = 0; t < tasks; ++t) CHECK(runs[t].load() == 1);
    }
    std::atomic<int> ran{0};
    CHECK_THROWS_WITH(pool.run(5,
                               [&](size_t t, int) {
                                 ran.fetch_add(1);
                                 if (t == 2) throw std::runtime_error("task 2 failed");
                               }),
                      "task 2 failed");
    CHECK(ran.load() == 5);  // the others still ran
    std::atomic<int> after{0};
    pool.run(4, [&](size_t, int) { after.fetch_add(1); });  // the pool is still usable
    CHECK(after.load() == 4);
  }
  CHECK_THROWS_AS(ThreadPool(0), InputError);
}

TEST_CASE("a thread pool runs released tasks while the producer is still preparing the next", "[cpu]") {
  for (const int threads : {1, 3}) {
    ThreadPool pool(threads);
    std::vector<std::atomic<int>> runs(4);
    std::vector<int> ready(4, 0);
    std::atomic<bool> overlapped{false}, early{false};
    pool.run_as_released(
        4,
        [&](const std::function<void()>& release) {
          for (size_t t = 0; t < 4; ++t) {
            ready[t] = 1;  // the task's input, written before its release
            release();
            if (threads > 1 && t == 0) {
              // A worker takes task 0 while this thread still holds tasks 1-3 back.
              const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
              while (runs[0].load() == 0 && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
              overlapped = runs[0].load() == 1;
            }
          }
        },
        [&](size_t t, int) {
          if (ready[t] != 1) early = true;
          runs[t].fetch_add(1);
        });
    CHECK_FALSE(early.load());
    for (auto& r : runs) CHECK(r.load() == 1);
    if (threads > 1) CHECK(overlapped.load());
    // A producer that fails after releasing two tasks: those two run, the others never, and its
    // exception is the one that arrives.
    std::atomic<int> ran{0};
    CHECK_THROWS_WITH(pool.run_as_released(
                          5,
                          [&](const std::function<void()>& release) {
                            release();
                            release();
                            throw std::runtime_error("producer failed");
                          },
                          [&](size_t t, int) {
                            ran.fetch_add(1);
                            if (t == 1) throw std::runtime_error("task failed");
                          }),
                      "producer failed");
    CHECK(ran.load() == 2);
    std::atomic<int> after{0};
    pool.run(3, [&](size_t, int) { after.fetch_add(1); });  // still usable
    CHECK(after.load() == 3);
  }
}

namespace {

// The filter's whole state and output after each frame must be identical, not close.
void check_identical(const reference::ReferenceFilter& a, const reference::ReferenceFilter& b, const Estimate& ea,
                     const Estimate& eb) {
  CHECK(ea.pose.translation == eb.pose.translation);
  CHECK(ea.pose.rotation.coeffs() == eb.pose.rotation.coeffs());
  CHECK(ea.effective_sample_size == eb.effective_sample_size);
  CHECK(ea.resampled == eb.resampled);
  CHECK(ea.max_log_likelihood == eb.max_log_likelihood);
  // NaN where the fit left the covariance undetermined: NaN in the same entries counts as equal.
  CHECK((ea.covariance.array() == eb.covariance.array() ||
         (ea.covariance.array().isNaN() && eb.covariance.array().isNaN()))
            .all());
  CHECK(a.last_log_likelihoods() == b.last_log_likelihoods());
  CHECK(a.log_weights() == b.log_weights());
  CHECK(a.last_parents() == b.last_parents());
  CHECK(a.occlusion_state() == b.occlusion_state());
  CHECK(a.occlusion_times() == b.occlusion_times());
  REQUIRE(a.particles().size() == b.particles().size());
  for (size_t i = 0; i < a.particles().size(); ++i) {
    CHECK(a.particles()[i].pose.translation == b.particles()[i].pose.translation);
    CHECK(a.particles()[i].pose.rotation.coeffs() == b.particles()[i].pose.rotation.coeffs());
  }
}

}  // namespace

TEST_CASE("the cpu backend equals the sequential reference bit for bit, frame by frame", "[cpu][filter]") {
  const Mesh mesh = builtin_demo_mesh();
  SynthConfig synth;
  synth.frames = 8;
  synth.occluder_fraction = 0.3;
  synth.camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
  const auto frames = test::synthesize(mesh, synth);
  for (const auto mode : {OcclusionStorage::PerPixelTime, OcclusionStorage::GlobalTime}) {
    TrackerConfig config;
    config.particles = 61;  // not a multiple of the thread count: chunks of unequal size
    config.occlusion_storage = mode;
    config.seed = 5;
    config.resample_kl_threshold = 0.5;  // resample often, so the parallel gather is exercised
    reference::ReferenceFilter sequential(mesh, synth.camera, config, 1);
    reference::ReferenceFilter threaded(mesh, synth.camera, config, 3);
    CHECK(threaded.description() == "cpu (the reference filter on 3 threads)");
    sequential.initialize(frames[0].ground_truth, InitialSpread{0.01, 0.05});
    threaded.initialize(frames[0].ground_truth, InitialSpread{0.01, 0.05});
    int resampled = 0;
    for (size_t f = 0; f < frames.size(); ++f) {
      INFO("frame " << f);
      const double dt = f == 0 ? 0.0 : frames[f].timestamp - frames[f - 1].timestamp;
      const Estimate a = sequential.update(frames[f].depth, dt);
      const Estimate b = threaded.update(frames[f].depth, dt);
      resampled += a.resampled ? 1 : 0;
      check_identical(sequential, threaded, a, b);
    }
    CHECK(resampled > 0);
    // Scoring (global search) too, with more poses than threads and fewer.
    for (const size_t count : {size_t{2}, size_t{13}}) {
      std::vector<Pose> poses;
      for (size_t i = 0; i < count; ++i) {
        Pose p = frames[0].ground_truth;
        p.translation.x() += 0.004 * static_cast<double>(i);
        poses.push_back(p);
      }
      const auto sa = sequential.score_poses(poses, frames[0].depth, config.observation);
      const auto sb = threaded.score_poses(poses, frames[0].depth, config.observation);
      CHECK(sa == sb);
      CHECK(sequential.last_score_magnitudes() == threaded.last_score_magnitudes());
    }
  }
}

TEST_CASE("the weighted mean pose on a thread pool equals the sequential one bit for bit", "[cpu]") {
  // Weights spanning six orders of magnitude and rotations up to about 1 rad apart: sums taken in another
  // order (per thread, then combined) round differently in the last bits.
  std::vector<Pose> poses;
  std::vector<double> weights;
  double total = 0;
  for (int i = 0; i < 1001; ++i) {
    const double t = static_cast<double>(i);
    const Eigen::Vector3d axis = Eigen::Vector3d(std::sin(1.3 * t), std::cos(0.7 * t), std::sin(2.1 * t) + 1.5);
    poses.emplace_back(Eigen::Vector3d(0.01 * std::sin(t), 0.02 * std::cos(3 * t), 0.6 + 0.001 * t),
                       Eigen::Quaterniond(Eigen::AngleAxisd(std::fmod(0.37 * t, 1.0), axis.normalized())));
    weights.push_back(std::pow(10.0, -6.0 * std::fmod(0.61 * t, 1.0)));
    total += weights.back();
  }
  for (double& w : weights) w /= total;
  const Eigen::Vector3d centre(0.01, -0.02, 0.03);
  // The mean as one sequential loop states it (pose_mean.hpp), the heaviest pose's rotation to start from.
  Eigen::Vector3d mean_centre = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < poses.size(); ++i) mean_centre += weights[i] * poses[i].apply(centre);
  Eigen::Quaterniond mean =
      poses[static_cast<size_t>(std::max_element(weights.begin(), weights.end()) - weights.begin())].rotation;
  for (int iteration = 0; iteration < 4; ++iteration) {
    Eigen::Vector3d step = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < poses.size(); ++i) step += weights[i] * rotation_log(mean.conjugate() * poses[i].rotation);
    mean = (mean * rotation_exp(step)).normalized();
  }
  const Pose sequential(mean_centre - mean * centre, mean);
  CHECK(reference::weighted_mean_pose(poses, weights, centre).translation == sequential.translation);
  for (const int threads : {1, 2, 3}) {
    INFO(threads << " threads");
    ThreadPool pool(threads);
    const Pose pooled = reference::weighted_mean_pose(poses, weights, centre, &pool);
    CHECK(pooled.translation == sequential.translation);
    CHECK(pooled.rotation.coeffs() == sequential.rotation.coeffs());
  }
}

TEST_CASE("the cpu backend is named cpu or cpu:N and refuses a bad thread count", "[cpu]") {
  const Mesh mesh = builtin_demo_mesh();
  const Camera camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
  TrackerConfig config;
  config.particles = 4;
  config.backend = "cpu:2";
  CHECK(make_filter_backend(mesh, camera, config)->description() == "cpu (the reference filter on 2 threads)");
  config.backend = "cpu";
  const int threads = hardware_threads();
  CHECK(make_filter_backend(mesh, camera, config)->description() ==
        (threads == 1 ? std::string("reference (sequential CPU)")
                      : "cpu (the reference filter on " + std::to_string(threads) + " threads)"));
  for (const char* bad : {"cpu:0", "cpu:", "cpu:2x", "cpu:-1", "cpu:5000"}) {
    INFO(bad);
    config.backend = bad;
    try {
      make_filter_backend(mesh, camera, config);
      FAIL("accepted");
    } catch (const InputError& e) {
      CHECK_THAT(e.what(), Contains(bad) && Contains("thread count"));
    }
  }
}

TEST_CASE("the cpu backend's thread count is the CPUs the process may run on", "[cpu]") {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  REQUIRE(sched_getaffinity(0, sizeof(allowed), &allowed) == 0);
  CHECK(hardware_threads() == CPU_COUNT(&allowed));
  // Pinned to one of them, as under taskset -c N: one thread, however many the machine has.
  int first = 0;
  while (!CPU_ISSET(first, &allowed)) ++first;
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(first, &one);
  REQUIRE(sched_setaffinity(0, sizeof(one), &one) == 0);
  const int pinned = hardware_threads();
  REQUIRE(sched_setaffinity(0, sizeof(allowed), &allowed) == 0);
  CHECK(pinned == 1);
}

TEST_CASE("a Tracker on cpu:2 reports what one on the reference reports, status and confidence included", "[cpu]") {
  const Mesh mesh = builtin_demo_mesh();
  SynthConfig synth;
  synth.frames = 5;
  synth.occluder_fraction = 0.3;
  synth.camera = Camera::make(160, 120, 131.25, 131.25, 79.875, 59.875);
  const auto frames = test::synthesize(mesh, synth);
  TrackerConfig config;
  config.particles = 40;
  Tracker sequential(mesh, synth.camera, config);
  config.backend = "cpu:2";
  Tracker threaded(mesh, synth.camera, config);
  CHECK_THAT(threaded.backend_description(), Contains("2 threads"));
  sequential.initialize(frames[0].ground_truth);
  threaded.initialize(frames[0].ground_truth);
  for (const SynthFrame& f : frames) {
    const Estimate a = sequential.update(f.depth, f.timestamp);
    const Estimate b = threaded.update(f.depth, f.timestamp);
    CHECK(a.pose.translation == b.pose.translation);
    CHECK(a.pose.rotation.coeffs() == b.pose.rotation.coeffs());
    CHECK(a.confidence == b.confidence);
    CHECK(a.status == b.status);
  }
}
