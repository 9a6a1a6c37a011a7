// The device fit's variants that must give the same fit, bit for bit: the one-launch fit that summarizes
// in its own launch (cl/refine_spread.cl's refine_one_launch with summarize, the filter's default on
// OpenCL below 2,048 triangles) against summarize.cl followed by the fit alone (both summaries over groups
// of the same size); and each layout's drawing split over rows (DeviceRefiner's draw_slices) against
// each triangle drawn whole.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstring>
#include <depthtrack/error.hpp>
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

namespace {
// A cloud 1-2 cm and a few degrees off the truth, its observed frame the mesh drawn at the truth before a
// wall, and what a fit of it returns.
struct FitScene {
  Camera camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
  Mesh mesh;
  Pose truth{{0.01, -0.01, 0.8}, rotation_exp(Eigen::Vector3d(0.4, 0.5, 0.1))};
  std::vector<float> observed;
  std::vector<model::ParticleState> particles;
  std::vector<float> log_weight, log_likelihood;
  std::vector<unsigned> parents;
  dt_window window{0, 0, 0, 0, 80, 60, 80, 60, 80, 0.1f};
  float kl_threshold = 0.5f;
};

FitScene fit_scene(const Mesh& mesh, const TrackerConfig& config, size_t count) {
  FitScene scene;
  scene.mesh = mesh;
  scene.observed.resize(static_cast<size_t>(scene.camera.pixel_count()));
  reference::Rasterizer(mesh, scene.camera, config.near_plane, config.observation.max_depth)
      .render(scene.truth, scene.observed);
  for (float& y : scene.observed)
    if (y == 0) y = 1.5f;  // a wall behind the object
  // Log weights spread over a few nats so that many particles carry weight and the heaviest is not the first.
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  scene.particles.resize(count);
  scene.log_weight.resize(count);
  scene.log_likelihood.resize(count);
  for (size_t i = 0; i < count; ++i) {
    scene.particles[i].pose =
        model::move_about_centre(scene.truth, Eigen::Vector3d::Zero(),
                                 Eigen::Vector3d(0.01 * normal(rng), 0.01 * normal(rng), 0.01 * normal(rng)),
                                 Eigen::Vector3d(0.05 * normal(rng), 0.05 * normal(rng), 0.05 * normal(rng)));
    scene.particles[i].linear_velocity = Eigen::Vector3d(0.1 * normal(rng), 0.0, 0.05);
    scene.log_likelihood[i] = static_cast<float>(-1000.0 + 3.0 * normal(rng));
    scene.log_weight[i] = scene.log_likelihood[i] + static_cast<float>(normal(rng));
  }
  scene.parents.resize(count);
  for (size_t i = 0; i < count; ++i) scene.parents[i] = static_cast<unsigned>(i);
  return scene;
}

struct FitRun {
  std::vector<float> estimate, weights, correction;
};

// The scene's fit with config's layout, its drawing split draw_slices ways (0: the device's choice): after
// summarize.cl over groups of the fit's size (256, as the one-launch fit's summary sums), or with
// own_summary in the fit's own launch.
FitRun run_fit(compute::Queue& q, compute::ProgramCache& programs, const FitScene& scene, const TrackerConfig& config,
               unsigned draw_slices, bool own_summary) {
  const size_t pixels = scene.observed.size(), count = scene.particles.size();
  DeviceRefiner refiner(q, programs, scene.mesh, scene.camera, config, "DT_OCCLUSION=0", draw_slices);
  REQUIRE(refiner.layout() == config.refine.layout);
  if (draw_slices > 0) REQUIRE(refiner.draw_slices() == draw_slices);
  compute::Buffer<float> states(q, count * DT_STATE_STRIDE), obs(q, pixels), lw(q, count), ll(q, count),
      weights(q, count), estimate(q, DT_EST_SIZE), occlusion(q, count * pixels), frame_times(q, DT_TIME_TABLE);
  compute::Buffer<uint16_t> occlusion_time(q, count * pixels);
  compute::Buffer<unsigned> parent_buffer(q, count);
  states.upload(pack_particles(scene.particles));
  obs.upload(scene.observed);
  lw.upload(scene.log_weight);
  ll.upload(scene.log_likelihood);
  estimate.upload(std::vector<float>(DT_EST_SIZE, -7.0f));
  occlusion.upload(std::vector<float>(count * pixels, 0.1f));
  occlusion_time.upload(std::vector<uint16_t>(count * pixels, 0));
  frame_times.upload(std::vector<float>(DT_TIME_TABLE, 0.0f));
  parent_buffer.upload(scene.parents);
  const RefineInputs inputs{states,        obs,          occlusion, occlusion_time, frame_times,
                            parent_buffer, scene.window, 0.1,       1.0 / 30};
  const Eigen::Vector3f centre = scene.mesh.centre();
  if (own_summary) {
    REQUIRE(refiner.summarizes_first());
    const SummaryInputs summary{lw, ll, weights, static_cast<unsigned>(count), centre, scene.kl_threshold};
    refiner.refine(estimate, inputs, &summary);
  } else {
    auto summarize = programs.program("summarize.cl", {"DT_GROUP_SIZE=256", "DT_OCCLUSION=0"})->kernel("summarize");
    q.launch(*summarize, compute::NdRange::linear(256, 256), states, lw, ll, weights, estimate,
             static_cast<unsigned>(count), centre.x(), centre.y(), centre.z(), scene.kl_threshold, 0u);
    refiner.refine(estimate, inputs);
  }
  q.finish();
  return FitRun{estimate.download(), weights.download(), refiner.correction().download()};
}

Pose fitted_pose(const std::vector<float>& e) {
  return Pose({e[DT_EST_TX], e[DT_EST_TX + 1], e[DT_EST_TX + 2]},
              Eigen::Quaterniond(e[DT_EST_QW], e[DT_EST_QW + 1], e[DT_EST_QW + 2], e[DT_EST_QW + 3]));
}

// Bit for bit (memcmp: NaN-free here, but == would hide a -0 against +0).
bool same_floats(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}
}  // namespace

TEST_CASE("The one-launch fit's own summary equals summarize then the fit, bit for bit", "[device][refine]") {
  if (!test::device_available()) return;
  auto q = compute::open_device(test::device_selector());
  if (!q->info().int64_atomics) {
    SUCCEED("SKIPPED: one-launch needs 64-bit atomic min, which " + q->info().name + " does not list");
    return;
  }
  TrackerConfig config;
  config.refine.layout = RefineLayout::OneLaunch;
  config.step_timings = false;
  const FitScene scene = fit_scene(builtin_demo_mesh(), config, 300);
  compute::ProgramCache programs(*q);
  const FitRun apart = run_fit(*q, programs, scene, config, 0, false),
               together = run_fit(*q, programs, scene, config, 0, true);
  CHECK(same_floats(together.estimate, apart.estimate));
  CHECK(same_floats(together.weights, apart.weights));
  CHECK(same_floats(together.correction, apart.correction));
  // And it did summarize and fit: weights that sum to 1, steps taken, the estimate moved off the heaviest
  // particle towards the truth.
  double total = 0;
  for (const float w : together.weights) total += w;
  CHECK(total == Approx(1.0).epsilon(1e-5));
  const std::vector<float>& e = together.estimate;
  CHECK(e[DT_EST_REFINE_ITERATIONS] >= 1);
  const auto heaviest = static_cast<size_t>(std::max_element(scene.log_weight.begin(), scene.log_weight.end()) -
                                            scene.log_weight.begin());
  CHECK(translation_error(fitted_pose(e), scene.truth) <
        0.5 * translation_error(scene.particles[heaviest].pose, scene.truth));
}

TEST_CASE("The fit's drawing split over rows: at most a row per slice, more on a GPU for coarse meshes", "[refine]") {
  // Spread: ceil(2,048 / triangles); one group: floor(256 / triangles), its idle work-items only; at most the
  // image's rows and 64; 1 on a CPU.
  const RefineLayout spread = RefineLayout::Spread, one_launch = RefineLayout::OneLaunch;
  CHECK(refine_draw_slices(spread, 246, 60, true) == 9);
  CHECK(refine_draw_slices(spread, 2048, 60, true) == 1);
  CHECK(refine_draw_slices(spread, 3196, 60, true) == 1);
  CHECK(refine_draw_slices(spread, 1000, 60, true) == 3);
  CHECK(refine_draw_slices(spread, 12, 60, true) == 60);
  CHECK(refine_draw_slices(spread, 12, 480, true) == 64);
  CHECK(refine_draw_slices(spread, 12, 480, false) == 1);
  CHECK(refine_draw_slices(spread, 0, 60, true) == 1);
  CHECK(refine_draw_slices(one_launch, 246, 60, true) == 1);
  CHECK(refine_draw_slices(one_launch, 842, 60, true) == 1);
  CHECK(refine_draw_slices(one_launch, 100, 60, true) == 2);
  CHECK(refine_draw_slices(RefineLayout::OneGroup, 12, 60, true) == 21);
  CHECK(refine_draw_slices(one_launch, 12, 60, false) == 1);
}

TEST_CASE("A fit whose drawing is split over rows equals the fit drawing each triangle whole, bit for bit",
          "[device][refine]") {
  if (!test::device_available()) return;
  auto q = compute::open_device(test::device_selector());
  compute::ProgramCache programs(*q);
  TrackerConfig config;
  config.step_timings = false;
  // A box whose 12 large triangles each span several of the 80x60 image's rows, and the demo mesh's smaller ones.
  for (const Mesh& mesh : {make_box(Eigen::Vector3f(0.12f, 0.08f, 0.06f)), builtin_demo_mesh()}) {
    const FitScene scene = fit_scene(mesh, config, 64);
    for (const RefineLayout layout : {RefineLayout::OneGroup, RefineLayout::Spread, RefineLayout::OneLaunch}) {
      if (layout != RefineLayout::OneGroup && !q->info().int64_atomics) continue;
      config.refine.layout = layout;
      const FitRun whole = run_fit(*q, programs, scene, config, 1, false);
      INFO(mesh.triangles.size() << " triangles, layout " << to_string(layout));
      // The fit took steps and came nearer the truth, so the drawings it compares are many and differ.
      REQUIRE(whole.estimate[DT_EST_REFINE_ITERATIONS] >= 1);
      const auto heaviest = static_cast<size_t>(std::max_element(scene.log_weight.begin(), scene.log_weight.end()) -
                                                scene.log_weight.begin());
      CHECK(translation_error(fitted_pose(whole.estimate), scene.truth) <
            translation_error(scene.particles[heaviest].pose, scene.truth));
      for (const unsigned slices : {2u, 7u, 60u}) {
        INFO(slices << " slices");
        const FitRun split = run_fit(*q, programs, scene, config, slices, false);
        CHECK(same_floats(split.estimate, whole.estimate));
        CHECK(same_floats(split.correction, whole.correction));
      }
    }
  }
}
