// The one-launch fit that summarizes in its own launch (cl/refine_spread.cl's refine_one_launch with
// summarize, the filter's default on OpenCL below 2,048 triangles) against summarize.cl followed by the
// fit alone: with both summaries over groups of the same size, the same estimate, weights and
// correction, bit for bit.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstring>
#include <depthtrack/pose.hpp>
#include <random>

#include "compute/buffer.hpp"
#include "compute/kernel_sources.hpp"
#include "compute/program_cache.hpp"
#include "device_support.hpp"
#include "dt_state.h"
#include "dt_time_index.h"
#include "filter/device_refiner.hpp"
#include "model/kernel_params.hpp"
#include "model/particle.hpp"
#include "model/particle_packing.hpp"
#include "reference/rasterizer.hpp"

using namespace depthtrack;

TEST_CASE("The one-launch fit's own summary equals summarize then the fit, bit for bit", "[device][refine]") {
  if (!test::device_available()) return;
  auto q = compute::open_device(test::device_selector());
  if (!q->info().int64_atomics) {
    SUCCEED("SKIPPED: one-launch needs 64-bit atomic min, which " + q->info().name + " does not list");
    return;
  }
  const Camera camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
  const size_t pixels = 4800, count = 300;
  const Mesh mesh = builtin_demo_mesh();
  TrackerConfig config;
  config.refine.layout = RefineLayout::OneLaunch;
  config.step_timings = false;
  const Pose truth({0.01, -0.01, 0.8}, rotation_exp(Eigen::Vector3d(0.4, 0.5, 0.1)));
  std::vector<float> observed(pixels);
  reference::Rasterizer(mesh, camera, config.near_plane, config.observation.max_depth).render(truth, observed);
  for (float& y : observed)
    if (y == 0) y = 1.5f;  // a wall behind the object
  // Particles 1-2 cm and a few degrees off the truth, log weights spread over a few nats so that many
  // particles carry weight and the heaviest is not the first.
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  std::vector<model::ParticleState> particles(count);
  std::vector<float> log_weight(count), log_likelihood(count);
  for (size_t i = 0; i < count; ++i) {
    particles[i].pose = model::move_about_centre(
        truth, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.01 * normal(rng), 0.01 * normal(rng), 0.01 * normal(rng)),
        Eigen::Vector3d(0.05 * normal(rng), 0.05 * normal(rng), 0.05 * normal(rng)));
    particles[i].linear_velocity = Eigen::Vector3d(0.1 * normal(rng), 0.0, 0.05);
    log_likelihood[i] = static_cast<float>(-1000.0 + 3.0 * normal(rng));
    log_weight[i] = log_likelihood[i] + static_cast<float>(normal(rng));
  }
  std::vector<unsigned> parents(count);
  for (size_t i = 0; i < count; ++i) parents[i] = static_cast<unsigned>(i);
  const dt_window window{0, 0, 0, 0, 80, 60, 80, 60, 80, 0.1f};
  const float kl_threshold = 0.5f;
  const Eigen::Vector3f centre = mesh.centre();

  compute::ProgramCache programs(*q);
  // summarize.cl over groups of the fit's size (256), as the one-launch fit's summary sums.
  auto summarize_program = programs.program("summarize.cl", {"DT_GROUP_SIZE=256", "DT_OCCLUSION=0"});
  auto summarize = summarize_program->kernel("summarize");
  struct Run {
    std::vector<float> estimate, weights, correction;
  };
  auto run = [&](bool own_summary) {
    DeviceRefiner refiner(*q, programs, mesh, camera, config, "DT_OCCLUSION=0");
    REQUIRE(refiner.layout() == RefineLayout::OneLaunch);
    REQUIRE(refiner.summarizes_first());
    compute::Buffer<float> states(*q, count * DT_STATE_STRIDE), obs(*q, pixels), lw(*q, count), ll(*q, count),
        weights(*q, count), estimate(*q, DT_EST_SIZE), occlusion(*q, count * pixels), frame_times(*q, DT_TIME_TABLE);
    compute::Buffer<uint16_t> occlusion_time(*q, count * pixels);
    compute::Buffer<unsigned> parent_buffer(*q, count);
    states.upload(pack_particles(particles));
    obs.upload(observed);
    lw.upload(log_weight);
    ll.upload(log_likelihood);
    estimate.upload(std::vector<float>(DT_EST_SIZE, -7.0f));
    occlusion.upload(std::vector<float>(count * pixels, 0.1f));
    occlusion_time.upload(std::vector<uint16_t>(count * pixels, 0));
    frame_times.upload(std::vector<float>(DT_TIME_TABLE, 0.0f));
    parent_buffer.upload(parents);
    const RefineInputs inputs{states,        obs,    occlusion, occlusion_time, frame_times,
                              parent_buffer, window, 0.1,       1.0 / 30};
    if (own_summary) {
      const SummaryInputs summary{lw, ll, weights, static_cast<unsigned>(count), centre, kl_threshold};
      refiner.refine(estimate, inputs, &summary);
    } else {
      q->launch(*summarize, compute::NdRange::linear(256, 256), states, lw, ll, weights, estimate,
                static_cast<unsigned>(count), centre.x(), centre.y(), centre.z(), kl_threshold, 0u);
      refiner.refine(estimate, inputs);
    }
    q->finish();
    return Run{estimate.download(), weights.download(), refiner.correction().download()};
  };
  const Run apart = run(false), together = run(true);
  // Bit for bit (memcmp: NaN-free here, but == would hide a -0 against +0).
  CHECK(std::memcmp(together.estimate.data(), apart.estimate.data(), DT_EST_SIZE * sizeof(float)) == 0);
  CHECK(std::memcmp(together.weights.data(), apart.weights.data(), count * sizeof(float)) == 0);
  CHECK(std::memcmp(together.correction.data(), apart.correction.data(), 6 * sizeof(float)) == 0);
  // And it did summarize and fit: weights that sum to 1, steps taken, the estimate moved off the heaviest
  // particle towards the truth.
  double total = 0;
  for (const float w : together.weights) total += w;
  CHECK(total == Approx(1.0).epsilon(1e-5));
  const std::vector<float>& e = together.estimate;
  CHECK(e[DT_EST_REFINE_ITERATIONS] >= 1);
  const unsigned heaviest =
      static_cast<unsigned>(std::max_element(log_weight.begin(), log_weight.end()) - log_weight.begin());
  const Pose fitted({e[DT_EST_TX], e[DT_EST_TX + 1], e[DT_EST_TX + 2]},
                    Eigen::Quaterniond(e[DT_EST_QW], e[DT_EST_QW + 1], e[DT_EST_QW + 2], e[DT_EST_QW + 3]));
  CHECK(translation_error(fitted, truth) < 0.5 * translation_error(particles[heaviest].pose, truth));
}
