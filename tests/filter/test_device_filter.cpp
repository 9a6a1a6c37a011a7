// The device filter (compute kernels) against the reference filter: same seed, same frames ->
// the same log-likelihoods (to float precision), the same resampling ancestry, the same estimates.
#include <catch2/catch.hpp>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <depthtrack/synth.hpp>

#include "device_support.hpp"
#include "filter/device_filter.hpp"
#include "filter/device_filter_probe.hpp"
#include "filter/device_refiner.hpp"
#include "filter/wide_summary.hpp"
#include "model/occlusion_chain.hpp"
#include "model/state_window.hpp"
#include "philox.h"
#include "reference/observation_model.hpp"
#include "reference/reference_filter.hpp"
#include "reference/weights.hpp"
#ifdef DEPTHTRACK_WITH_GL
#include "atlas/gl/gl_context.hpp"
#endif
#include "support.hpp"
#include "equivalent_fit.hpp"

using namespace depthtrack;

namespace {
struct Scene {
  Mesh mesh;
  std::string name;
  std::vector<SynthFrame> frames;
  Camera working;
};

size_t scene_pixels(const Scene& scene) {
  return static_cast<size_t>(scene.working.pixel_count());
}

// The handset when ../shared is there, else the built-in object; 30 % occluded, decimated to 80x60
// (decimation 8 of the 640x480 sensor). `path` moves it; the frames before `skip` are left out.
Scene make_scene(int frames, int decimation = 8, const TrajectoryModel& path = {}, int skip = 0) {
  Scene s;
  const char* env = std::getenv("DEPTHTRACK_DATA_DIR");
  const auto handset = std::filesystem::path(env ? env : DEPTHTRACK_DATA_DIR) / "meshes/dbot/handset.obj";
  s.name = std::filesystem::exists(handset) ? "handset" : "builtin";
  s.mesh = s.name == "handset" ? Mesh::load(handset) : builtin_demo_mesh();
  SynthConfig synth;
  synth.frames = skip + frames;
  synth.occluder_fraction = 0.3;
  synth.trajectory = path;
  const Synthesizer synthesizer(s.mesh, synth);
  for (int i = skip; i < skip + frames; ++i) {
    SynthFrame f = synthesizer.frame(i);
    f.depth = f.depth.decimated(decimation);
    s.frames.push_back(std::move(f));
  }
  s.working = synth.camera.decimated(decimation);
  return s;
}

// The time from frame f - 1 to frame f (0 for the first: the start's frame propagates nothing).
double frame_dt(const Scene& scene, size_t f) {
  return f == 0 ? 0.0 : scene.frames[f].timestamp - scene.frames[f - 1].timestamp;
}

// The reference's log-likelihood of one particle from a given rendering (its atlas tile) and a
// snapshot of its occlusion state before the frame.
// The snapshot's rows lie in the state window `before`; this frame's is `window` (a pixel outside it,
// or new to it, is fresh: occlusion.initial aged from time 0).
double reference_log_likelihood(const TrackerConfig& config, std::span<const float> rendered, const DepthImage& depth,
                                const std::vector<float>& occlusion, const std::vector<float>& times, size_t particle,
                                double now, double dt, const model::StateWindow& before,
                                const model::StateWindow& window) {
  const size_t pixels = rendered.size();
  const int width = depth.width();
  double sum = 0;
  for (size_t k = 0; k < pixels; ++k) {
    const float y = depth.data()[k];
    if (rendered[k] <= 0 || !DepthImage::is_valid(y)) continue;
    const int u = static_cast<int>(k) % width, v = static_cast<int>(k) / width;
    double p = model::propagate_occlusion(config.occlusion, config.occlusion.initial, now);
    if (config.occlusion_storage == OcclusionStorage::Off) p = 0;
    if (!window.contains(u, v) || !before.contains(u, v)) {
      sum += reference::pixel_log_ratio(reference::pixel_densities(config.observation, y, rendered[k]), p);
      continue;
    }
    const size_t at = particle * before.pixels() + before.index(u, v);
    if (config.occlusion_storage == OcclusionStorage::PerPixelTime)
      p = model::propagate_occlusion(config.occlusion, occlusion[at], now - times[at]);
    if (config.occlusion_storage == OcclusionStorage::GlobalTime)
      p = model::propagate_occlusion(config.occlusion, occlusion[at], dt);
    sum += reference::pixel_log_ratio(reference::pixel_densities(config.observation, y, rendered[k]), p);
  }
  return sum;
}

// Pixels whose coverage differs between a tile and the reference rasterization of the same pose.
int coverage_differences(const Scene& scene, const TrackerConfig& config, const Pose& pose,
                         std::span<const float> tile) {
  reference::Rasterizer r(scene.mesh, scene.working, config.near_plane, config.observation.max_depth);
  std::vector<float> rendered(tile.size());
  r.render(pose, rendered);
  int differences = 0;
  for (size_t k = 0; k < tile.size(); ++k) differences += (rendered[k] > 0) != (tile[k] > 0);
  return differences;
}

// The whole comparison, for one atlas renderer ("cpu": the reference rasterizer; "gl": OpenGL) and
// refinement layout (one group or spread over many: the same fit).
void compare_with_reference(const std::string& renderer, RefineLayout layout = RefineLayout::Auto,
                            OcclusionWindow window = {}, const Scene& scene = make_scene(20), int min_growths = 0) {
  const compute::DeviceInfo info = compute::open_device(test::device_selector())->info();
  for (auto mode : {OcclusionStorage::PerPixelTime, OcclusionStorage::GlobalTime, OcclusionStorage::Off}) {
    TrackerConfig config;
    config.renderer = renderer_from_string(renderer);
    config.particles = 200;
    config.occlusion_storage = mode;
    config.seed = 9;
    config.backend = test::device_selector();
    config.refine.layout = layout;
    config.occlusion_window = window;
    reference::ReferenceFilter reference(scene.mesh, scene.working, config);
    DeviceFilter device(compute::open_device(config.backend), scene.mesh, scene.working, config);
    DeviceFilterProbe(device).keep_atlas(true);  // a flipped pixel is checked against the tile the device weighed
    const InitialSpread spread{0.01, 0.05};
    reference.initialize(scene.frames[0].ground_truth, spread);
    device.initialize(scene.frames[0].ground_truth, spread);
    double worst_ll = 0, worst_t = 0, worst_r = 0, worst_ess = 0, worst_sd = 0, worst_confidence = 0;
    int undetermined_axes = 0;  // over the compared frames' covariances
    int resamplings = 0, ties = 0, apart_fits = 0, coverage_flips = 0, compared_frames = 0, window_moves = 0, window_growths = 0;
    for (size_t f = 0; f < scene.frames.size(); ++f) {
      const double dt = frame_dt(scene, f);
      const std::vector<float> occlusion_before = reference.occlusion_state(),
                               times_before = reference.occlusion_times();
      const model::StateWindow window_before = reference.state_window();
      const Estimate a = reference.update(scene.frames[f].depth, dt);
      const Estimate b = device.update(scene.frames[f].depth, dt);
      INFO(scene.name << ", " << to_string(mode) << ", frame " << f);
      // Both place the state window from their own estimates, the same pixel.
      REQUIRE(DeviceFilterProbe(device).state_window() == reference.state_window());
      window_moves += !(reference.state_window() == window_before);
      window_growths += reference.state_window().pixels() > window_before.pixels() && f > 0;
      const auto& ll_ref = reference.last_log_likelihoods();
      const auto& scale = reference.last_log_likelihood_magnitudes();
      const auto ll_dev = DeviceFilterProbe(device).last_log_likelihoods();
      const auto weighed = DeviceFilterProbe(device).weighed_particles();
      const auto atlas = DeviceFilterProbe(device).last_atlas();
      const size_t pixels = static_cast<size_t>(scene.working.pixel_count());
      bool flipped = false;
      for (size_t i = 0; i < ll_ref.size(); ++i) {
        // Relative to the sum's magnitude (sum of |per-pixel term|): a total near 0 cancels terms of
        // +-5, and float poses (1e-7 m) shift each term by about 1e-5.
        const double relative = std::abs(ll_ref[i] - ll_dev[i]) / std::max(1.0, scale[i]);
        INFO("particle " << i << ": reference " << ll_ref[i] << ", device " << ll_dev[i]);
        if (relative > 1e-4) {
          // A pixel centre within rounding of a silhouette edge is covered in one rendering and not in
          // the other (float pose; GL's fixed-point rasterization). Then the device's tile may differ
          // from the reference rasterization of its own pose at a few pixels only, and the device's
          // value must equal the reference formula applied to that tile.
          const std::span<const float> tile(atlas.data() + i * pixels, pixels);
          REQUIRE(coverage_differences(scene, config, weighed[i].pose, tile) <= 3);
          const double from_tile = reference_log_likelihood(
              config, tile, scene.frames[f].depth, occlusion_before, times_before, i,
              scene.frames[f].timestamp - scene.frames[0].timestamp, dt, window_before, reference.state_window());
          REQUIRE(std::abs(from_tile - ll_dev[i]) / std::max(1.0, scale[i]) <= 1e-4);
          ++coverage_flips;
          // Only a particle with weight can change ancestry or the estimate. The filters started the
          // frame from the same weights, so the device's weight is the reference's times e^(ll difference).
          const double w = reference.last_normalized_weights()[i];
          if (std::max(w, w * std::exp(ll_dev[i] - ll_ref[i])) > 1e-6) flipped = true;
          continue;
        }
        worst_ll = std::max(worst_ll, relative);
      }
      REQUIRE(a.resampled == b.resampled);
      const auto parents_ref = reference.last_parents(), parents_dev = DeviceFilterProbe(device).last_parents();
      if (parents_ref != parents_dev && !flipped) {
        // Allowed only where the device's own likelihoods, resampled by the reference's algorithm in
        // double, pick exactly the device's parents: the difference then lies wholly in likelihoods
        // already checked above (a numerical tie near a cumulative-weight boundary).
        std::vector<double> w = reference.last_normalized_weights();
        double sum = 0;
        for (size_t i = 0; i < w.size(); ++i) sum += w[i] *= std::exp(ll_dev[i] - ll_ref[i]);
        for (double& x : w) x /= sum;
        const double u =
            dt_uniform01(dt_random_words(config.seed, 0u, static_cast<dt_u32>(f), DT_STREAM_RESAMPLE, 0u).v[0]);
        REQUIRE(reference::systematic_resample(w, u) == parents_dev);
        ++ties;
      }
      // After a tie or a coverage flip the device restarts from the reference's state, so every
      // later frame is again compared from a common state.
      if (parents_ref != parents_dev || flipped)
        test::restart_from_reference(device, reference);
      resamplings += a.resampled;
      if (flipped) continue;  // a weighty particle's weight differs by the flipped pixel: not comparable
      if (!test::same_fit(a, b)) {
        // The fits went different ways from a decision at a threshold: equivalent, counted apart, and the
        // next frame starts from the reference's state.
        REQUIRE(config.refine.enabled);  // the filter alone has no fit to decide at a threshold
        const auto fits = test::compare_fits(reference, a, b, scene.frames[f].depth, scene.mesh);
        INFO("fit steps: reference " << a.refine_iterations << ", device " << b.refine_iterations
                                     << "; objective gap " << fits.objective_gap << ", largest axis d2 "
                                     << fits.axis_d2);
        REQUIRE(test::equivalent_fits(fits, config));
        ++apart_fits;
        test::restart_from_reference(device, reference);
        continue;
      }
      ++compared_frames;
      worst_t = std::max(worst_t, translation_error(a.pose, b.pose));
      worst_r = std::max(worst_r, rotation_error(a.pose, b.pose));
      // The confidence from the fit's counts at the refined pose (visible / measured pixels): a
      // silhouette pixel drawn in float rather than double moves it by about 1/400 on the handset.
      worst_confidence = std::max(worst_confidence, std::abs(b.confidence - a.confidence));
      REQUIRE(b.confidence == Approx(a.confidence).margin(0.02));
      if (config.refine.enabled) REQUIRE(a.confidence > 0.3);  // the object is seen: the counts are not empty
      // GL computes depth in float (~1e-6 relative), moving log-likelihoods by a few 0.01 nats and
      // weights by a few percent; the host rasterizer's atlas keeps ESS within 1e-3.
      const double ess_tolerance = renderer == "gl" ? 2e-2 : 1e-3;
      worst_ess = std::max(worst_ess, std::abs(b.effective_sample_size - a.effective_sample_size) /
                                          std::max(1.0, a.effective_sample_size));
      REQUIRE(b.effective_sample_size == Approx(a.effective_sample_size).epsilon(ess_tolerance).margin(1e-3));
      // The occlusion state the next frame starts from, in particle order (the device keeps each
      // particle's row where its parent's was until the next weigh copies it): the reference's, but
      // for the odd pixel of a particle whose silhouette flipped without weight to matter.
      if (mode != OcclusionStorage::Off) {
        const auto p_ref = reference.occlusion_state(), p_dev = DeviceFilterProbe(device).occlusion_state();
        const auto t_ref = reference.occlusion_times(), t_dev = DeviceFilterProbe(device).occlusion_times();
        REQUIRE(p_dev.size() == p_ref.size());
        REQUIRE(t_dev.size() == t_ref.size());
        size_t differing = 0;
        for (size_t k = 0; k < p_ref.size(); ++k)
          differing += std::abs(p_ref[k] - p_dev[k]) > 1e-4f || (!t_ref.empty() && t_ref[k] != t_dev[k]);
        INFO(differing << " of " << p_ref.size() << " pixel states differ from the reference's");
        // As many as one in a thousand of the whole image's pixel states (the flips lie on silhouettes,
        // whatever share of the image the state window holds).
        REQUIRE(differing <= static_cast<size_t>(config.particles) * scene.working.pixel_count() / 1000);
      }
      // The refined pose's covariance: per-axis standard deviations from the float normal equations.
      // With GL the fit's occlusion map follows GL's coverage of the heaviest tile (prior where it
      // covers), so a flipped silhouette pixel changes a pixel's weight in H: measured up to 3 %
      // on llvmpipe once the refinement stops at convergence (0.1 % for the host and kernel atlases).
      // CUDA's kernel atlas: up to 3.1 % on the handset (H200, 1 December 2026; the same with and without
      // --prec-div/--prec-sqrt), where the poses still agree within 1e-5 m: as with GL, a pixel more or
      // less in the fit's H. NVIDIA OpenCL stayed within 0.1 % in one group, and left it once Auto spread
      // its fit too: the spread sums' float order on a GPU, as on CUDA; the one-launch
      // layout's there 0.7 % (H100), and the one group's 0.7 % too on an H100 with
      // driver 580 (two builds). So every GPU is
      // held to 5 %; PoCL, any layout, stays within 0.1 %, and is held to it.
      const bool cuda = config.backend.rfind("cuda", 0) == 0;
      const double sd_tolerance = renderer == "gl" || cuda || info.is_gpu ? 5e-2 : 1e-3;
      // The built-in box (the scene without ../shared/data) is seen nearly face-on: its faces' depth
      // leaves sliding along them undetermined, and the normal equations are singular up to rounding.
      // Before such axes were set apart (model::pose_covariance, which makes both backends' covariance
      // from their H) double and float disagreed on which axes blew up or turned NaN (NaN vs 3 m, 5e4
      // vs 7.7, 0.014 vs NaN); now the float H and the double H must set apart the same axes
      // (+infinity) and agree on the others. The handset has every axis determined.
      for (int axis = 0; axis < 6; ++axis) {
        const bool undetermined = std::isinf(a.covariance(axis, axis));
        REQUIRE(std::isinf(b.covariance(axis, axis)) == undetermined);
        if (scene.name != "builtin") REQUIRE(!undetermined);
        undetermined_axes += undetermined;
        if (undetermined) continue;
        const double sd_ref = std::sqrt(a.covariance(axis, axis)), sd_dev = std::sqrt(b.covariance(axis, axis));
        REQUIRE(std::isfinite(sd_ref));
        worst_sd = std::max(worst_sd, std::abs(sd_dev - sd_ref) / sd_ref);
        REQUIRE(sd_dev == Approx(sd_ref).epsilon(sd_tolerance));
      }
    }
    std::printf(
        "%s, %s, renderer %s, refinement %s on %s: worst relative log-likelihood difference %.2g, estimates within "
        "%.2g m / %.2g rad, "
        "ESS within %.2g, refined standard deviations within %.2g (relative; %d undetermined axes), confidence within "
        "%.2g, "
        "%d resamplings, ancestry identical but for %d numerical ties; %d silhouette coverage flips; %d fits "
        "equivalent but apart; "
        "ancestry and estimates compared in %d of %zu frames; state window %dx%d moved %d times, grew %d times\n",
        scene.name.c_str(), to_string(mode), renderer.c_str(),
        to_string(resolved_refine_layout(layout, info, scene.mesh.triangles.size(), scene_pixels(scene))),
        device.description().c_str(), worst_ll, worst_t, worst_r, worst_ess, worst_sd, undetermined_axes,
        worst_confidence, resamplings, ties, coverage_flips, apart_fits, compared_frames, scene.frames.size(),
        reference.state_window().width, reference.state_window().height, window_moves, window_growths);
    CHECK(resamplings > 0);
    if (window.width > 0) CHECK(window_moves > 0);  // the rows followed the estimate
    CHECK(window_growths >= min_growths);
    CHECK(ties <= (renderer == "gl" ? 4 : 2));
    CHECK(apart_fits <= 2);
    // GL rasterizes in fixed point (llvmpipe: 1/256 px), so its silhouettes differ from the double
    // reference at about one pixel in 500 particle tiles; each is checked above. With the refinement
    // the cloud also moves by a float correction (~1e-7 m from the reference's): PoCL saw 0-3 flips.
    CHECK(coverage_flips <= (renderer == "gl" ? 300 : 6));
    CHECK(compared_frames >= (renderer == "gl" ? 10 : 15));
  }
}

// True when a headless GL context can be made here; otherwise prints a skip.
bool gl_available() {
#ifndef DEPTHTRACK_WITH_GL
  return test::gl_built();
#else
  try {
    render::GlContext context;
    return true;
  } catch (const std::exception& e) {
    std::cout << "SKIPPED: no OpenGL context: " << e.what() << "\n";
    return false;
  }
#endif
}
}  // namespace

TEST_CASE("device filter equals the reference filter frame by frame in every occlusion mode", "[device]") {
  if (!test::device_available()) return;
  compare_with_reference("cpu");
}

TEST_CASE("with the GL atlas in the loop the device filter still equals the reference", "[device][render]") {
  if (!test::device_available() || !gl_available()) return;
  compare_with_reference("gl");
}

TEST_CASE("with the compute-kernel atlas in the loop the device filter still equals the reference",
          "[device][kernel]") {
  if (!test::device_available()) return;
  compare_with_reference("kernel");
}

// A state window smaller than the handset's silhouette (about 18x12 pixels at 80x60), following the
// estimate: pixels outside it weighed with the fresh prior, rows moved, on the device as in the reference.
TEST_CASE("with a state window cutting the object the device filter still equals the reference",
          "[device][kernel][window]") {
  if (!test::device_available()) return;
  compare_with_reference("kernel", RefineLayout::Auto, OcclusionWindow{14, 10});
}

// The handset receding to 1.15 m by frame 18 of this path, then coming in to 0.78 m by frame 53: frames 18-53.
Scene nearing_scene() {
  TrajectoryModel nearing;
  nearing.amplitude = {0.02, 0.01, -0.35};
  nearing.period = 8.0;
  return make_scene(36, 8, nearing, 18);
}

// The automatic window (the default) grown while the object comes nearer: rows of the last frame's
// size read, rows of the new size written, on the device as in the reference.
TEST_CASE("with an automatic window growing as the object nears the device filter still equals the reference",
          "[device][kernel][window]") {
  if (!test::device_available()) return;
  compare_with_reference("kernel", RefineLayout::Auto, OcclusionWindow{}, nearing_scene(), 1);
}

// An automatic window's rows hold half as much again as its window: while the window stays within that
// (an estimate settling after its start, an object nearing a little) no state row is allocated again.
// Each reallocation's free waits for the device (every object's work queued on it) and changes the
// frame's graph: an H200 trace of ycbv-0000's first ten frames found such spikes in three
// objects' enqueue. The same nearing path.
TEST_CASE("an automatic window's rows have room for half as much again: growing within it allocates nothing",
          "[device][kernel][window]") {
  if (!test::device_available()) return;
  const Scene scene = nearing_scene();
  TrackerConfig config;
  config.particles = 50;
  config.seed = 9;
  config.backend = test::device_selector();
  DeviceFilter device(compute::open_device(config.backend), scene.mesh, scene.working, config);
  device.initialize(scene.frames[0].ground_truth, {0.01, 0.05});
  const size_t start_pixels = DeviceFilterProbe(device).state_window().pixels();
  // Probabilities and times, each in the current buffer (the start) and the scratch one (the first frame).
  const size_t first_frame_allocations = DeviceFilterProbe(device).state_row_allocations() + 2;
  bool grown_past_room = false;
  for (size_t f = 0; f < scene.frames.size(); ++f) {
    const double dt = frame_dt(scene, f);
    device.update(scene.frames[f].depth, dt);
    const size_t pixels = DeviceFilterProbe(device).state_window().pixels();  // the rows this frame wrote
    INFO("frame " << f << ": " << pixels << " pixels, " << start_pixels << " at the start");
    if (2 * pixels <= 3 * start_pixels) {
      CHECK(DeviceFilterProbe(device).state_row_allocations() == first_frame_allocations);
    } else {
      grown_past_room = true;
      CHECK(DeviceFilterProbe(device).state_row_allocations() > first_frame_allocations);
      break;
    }
  }
  CHECK(grown_past_room);  // the path comes near enough to test both sides
}

// Auto picks one layout per device and mesh (the test's handset: spread on GPUs, one group on
// CPUs); the other one, forced, must equal the reference just as well (the kernel atlas, as
// CI's default renderer).
// The rule behind Auto, from the measured costs in device_refiner.cpp: large meshes spread everywhere,
// small ones only on GPUs (PoCL's launches cost more than one group's loops).
TEST_CASE("the refinement layout auto spreads large meshes everywhere and small ones on GPUs, given 64-bit atomics",
          "[refine]") {
  compute::DeviceInfo cuda_gpu, opencl_gpu, opencl_cpu;
  cuda_gpu.backend = "cuda";
  cuda_gpu.replayed_launches = true;  // what CUDA's queue reports: batches replayed as graphs
  cuda_gpu.is_gpu = true;
  opencl_gpu.backend = "opencl";
  opencl_gpu.is_gpu = true;
  opencl_cpu.backend = "opencl";
  for (compute::DeviceInfo* d : {&cuda_gpu, &opencl_gpu, &opencl_cpu}) d->int64_atomics = true;
  const size_t handset = 842, mug = 16384, small = 80 * 60, large = 640 * 480;
  CHECK(resolved_refine_layout(RefineLayout::Auto, cuda_gpu, handset, small) == RefineLayout::Spread);
  CHECK(resolved_refine_layout(RefineLayout::Auto, opencl_gpu, handset, small) == RefineLayout::OneLaunch);
  CHECK(resolved_refine_layout(RefineLayout::Auto, opencl_cpu, handset, small) == RefineLayout::OneLaunch);
  CHECK(resolved_refine_layout(RefineLayout::Auto, cuda_gpu, mug, small) == RefineLayout::Spread);
  CHECK(resolved_refine_layout(RefineLayout::Auto, opencl_gpu, mug, small) == RefineLayout::Spread);
  CHECK(resolved_refine_layout(RefineLayout::Auto, opencl_cpu, mug, small) == RefineLayout::Spread);
  CHECK(resolved_refine_layout(RefineLayout::Auto, opencl_gpu, kSpreadTriangles - 1, small) == RefineLayout::OneLaunch);
  CHECK(resolved_refine_layout(RefineLayout::Auto, opencl_gpu, kSpreadTriangles, small) == RefineLayout::Spread);
  // A GPU spreads a large image's pixels over its groups; a CPU runs a group in sequence anyway.
  CHECK(resolved_refine_layout(RefineLayout::Auto, opencl_gpu, handset, kOneLaunchGpuPixels) ==
        RefineLayout::OneLaunch);
  CHECK(resolved_refine_layout(RefineLayout::Auto, opencl_gpu, handset, large) == RefineLayout::Spread);
  CHECK(resolved_refine_layout(RefineLayout::Auto, opencl_cpu, handset, large) == RefineLayout::OneLaunch);
  // A layout asked for is kept.
  CHECK(resolved_refine_layout(RefineLayout::OneGroup, cuda_gpu, mug, small) == RefineLayout::OneGroup);
  CHECK(resolved_refine_layout(RefineLayout::Spread, opencl_cpu, handset, small) == RefineLayout::Spread);
  CHECK(resolved_refine_layout(RefineLayout::OneLaunch, cuda_gpu, mug, small) == RefineLayout::OneLaunch);
  // The spread drawing keeps depth and triangle in one 64-bit atomic min: a device without it fits
  // in one group, and spread asked for there is refused by name.
  compute::DeviceInfo no_int64 = opencl_gpu;
  no_int64.int64_atomics = false;
  no_int64.name = "an old GPU";
  CHECK(resolved_refine_layout(RefineLayout::Auto, no_int64, mug, small) == RefineLayout::OneGroup);
  CHECK_THROWS_WITH(resolved_refine_layout(RefineLayout::Spread, no_int64, mug, small),
                    Catch::Contains("cl_khr_int64_extended_atomics") && Catch::Contains("an old GPU"));
  CHECK_THROWS_WITH(resolved_refine_layout(RefineLayout::OneLaunch, no_int64, mug, small),
                    Catch::Contains("one-launch") && Catch::Contains("an old GPU"));
}

// The other tests run auto's layout; here the device's other layouts, so that each is checked against
// the reference on every device (PoCL in CI: one-group and spread; CUDA: one-group and one-launch).
TEST_CASE("with each refinement layout auto does not pick the device filter still equals the reference",
          "[device][kernel][refine]") {
  if (!test::device_available()) return;
  const compute::DeviceInfo info = compute::open_device(test::device_selector())->info();
  const RefineLayout picked = resolved_refine_layout(RefineLayout::Auto, info, make_scene(1).mesh.triangles.size(),
                                                     scene_pixels(make_scene(1)));
  for (const RefineLayout layout : {RefineLayout::OneGroup, RefineLayout::Spread, RefineLayout::OneLaunch}) {
    if (layout == picked) continue;
    if (layout != RefineLayout::OneGroup && !info.int64_atomics) {
      std::cout << "SKIPPED: " << to_string(layout) << " on " << info.name << ": no 64-bit atomic min\n";
      continue;
    }
    INFO("layout " << to_string(layout));
    compare_with_reference("kernel", layout);
  }
}

// At 320x240 the spread sums kernel has 300 groups' worth of pixels, clamped to 256 groups (work-items
// sum several pixels), and its last group adds 256 stamped rows per evaluation. From a common state
// each frame (the reference's), the device's refined estimate must be the reference's.
// Both filters started alike; each frame the device starts from the reference's state, both update, and
// check sees the frame's index, both estimates and both filters.
template <class Check>
void each_frame_from_common_state(const Scene& scene, const TrackerConfig& config, Check check) {
  reference::ReferenceFilter reference(scene.mesh, scene.working, config);
  DeviceFilter device(compute::open_device(config.backend), scene.mesh, scene.working, config);
  const InitialSpread spread{0.01, 0.05};
  reference.initialize(scene.frames[0].ground_truth, spread);
  device.initialize(scene.frames[0].ground_truth, spread);
  for (size_t f = 0; f < scene.frames.size(); ++f) {
    INFO(scene.name << ", frame " << f);
    test::restart_from_reference(device, reference);
    const double dt = frame_dt(scene, f);
    const Estimate a = reference.update(scene.frames[f].depth, dt);
    const Estimate b = device.update(scene.frames[f].depth, dt);
    check(f, a, b, reference, device);
  }
}

// The reference's fit (a) and the device's (b) from a common state: the same refined pose, steps and
// confidence, and the covariance within the float sums' rounding.
void check_same_fit(const Estimate& a, const Estimate& b) {
  CHECK(translation_error(a.pose, b.pose) <= 1e-5);
  CHECK(rotation_error(a.pose, b.pose) <= 1e-4);
  CHECK(a.refine_iterations == b.refine_iterations);
  CHECK(std::abs(a.confidence - b.confidence) <= 0.02);
  for (int i = 0; i < 6; ++i)
    if (std::isfinite(a.covariance(i, i)) && a.covariance(i, i) > 0)
      CHECK(std::abs(b.covariance(i, i) / a.covariance(i, i) - 1) <= 0.05);
}

TEST_CASE("the spread refinement at 320x240 (more pixels than its groups' work-items) equals the reference",
          "[device][kernel][refine]") {
  if (!test::device_available()) return;
  const compute::DeviceInfo info = compute::open_device(test::device_selector())->info();
  if (!info.int64_atomics) {
    std::cout << "SKIPPED: " << info.name << " has no 64-bit atomic min (the spread layouts need it)\n";
    return;
  }
  const Scene scene = make_scene(4, 2);
  REQUIRE(scene.working.width == 320);
  // one-launch: its one group's work-items each sum 300 of the image's pixels.
  for (const RefineLayout layout : {RefineLayout::Spread, RefineLayout::OneLaunch}) {
    INFO("layout " << to_string(layout));
    TrackerConfig config;
    config.particles = 16;
    config.seed = 5;
    config.backend = test::device_selector();
    config.refine.layout = layout;
    int refined = 0;
    each_frame_from_common_state(scene, config, [&](size_t, const Estimate& a, const Estimate& b, auto&, auto&) {
      CHECK(translation_error(a.pose, b.pose) <= 1e-5);
      CHECK(rotation_error(a.pose, b.pose) <= 1e-4);
      CHECK(a.refine_iterations == b.refine_iterations);
      refined += a.refine_iterations > 0;
    });
    CHECK(refined > 0);  // the fit took steps: the rows were added and judged
  }
}

// Refinement::noise_scale reaches the device's fit as the reference's (model::fit_config on both sides):
// from a common state each frame, the same refined pose, steps and confidence, and the covariance at
// the filter's noise; and the scale changes the fit (a device that ignored it would fail the first).
TEST_CASE("a fit at half the filter's noise (refine.noise_scale 0.5) equals the reference's", "[device][refine]") {
  if (!test::device_available()) return;
  const Scene scene = make_scene(20);
  TrackerConfig config;
  config.particles = 64;
  config.seed = 3;
  config.backend = test::device_selector();
  config.refine.noise_scale = 0.5;
  std::vector<Pose> refined;
  each_frame_from_common_state(scene, config, [&](size_t, const Estimate& a, const Estimate& b, auto&, auto&) {
    check_same_fit(a, b);
    refined.push_back(a.pose);
  });
  config.refine.noise_scale = 1.0;
  double largest_move = 0;
  size_t frame = 0;
  each_frame_from_common_state(scene, config, [&](size_t f, const Estimate& a, const Estimate&, auto&, auto&) {
    largest_move = std::max(largest_move, translation_error(a.pose, refined[f]));
    frame = f;
  });
  CHECK(frame + 1 == refined.size());
  CHECK(largest_move > 1e-5);
}

// Refinement::fine_noise_scale: the fit's second stage, from the first stage's best pose at its own
// sigma(y), on the device as in the reference (model::fit_stages on both sides), in every layout the
// device has: from a common state each frame, the same refined pose, steps tried (both stages'),
// confidence and the covariance at the last stage's noise. The second stage moves the fit (a device
// that skipped it would fail the first checks) and tries steps of its own.
TEST_CASE("a fit with a second stage (refine.fine_noise_scale 0.35) equals the reference's in every layout",
          "[device][refine]") {
  if (!test::device_available()) return;
  const compute::DeviceInfo info = compute::open_device(test::device_selector())->info();
  const Scene scene = make_scene(12);
  TrackerConfig config;
  config.particles = 64;
  config.seed = 3;
  config.backend = test::device_selector();
  config.refine.fine_noise_scale = 0;
  std::vector<Pose> one_stage;
  std::vector<int> one_stage_steps;
  each_frame_from_common_state(scene, config, [&](size_t, const Estimate& a, const Estimate&, auto&, auto&) {
    one_stage.push_back(a.pose);
    one_stage_steps.push_back(a.refine_iterations);
  });
  config.refine.fine_noise_scale = 0.35;
  for (const RefineLayout layout : {RefineLayout::OneGroup, RefineLayout::Spread, RefineLayout::OneLaunch}) {
    if (layout != RefineLayout::OneGroup && !info.int64_atomics) {
      std::cout << "SKIPPED: " << to_string(layout) << " on " << info.name << ": no 64-bit atomic min\n";
      continue;
    }
    INFO("layout " << to_string(layout));
    config.refine.layout = layout;
    double largest_move = 0;
    int more_steps = 0;
    each_frame_from_common_state(scene, config, [&](size_t f, const Estimate& a, const Estimate& b, auto&, auto&) {
      check_same_fit(a, b);
      largest_move = std::max(largest_move, translation_error(b.pose, one_stage[f]));
      more_steps += b.refine_iterations > one_stage_steps[f];
    });
    CHECK(largest_move > 1e-5);
    CHECK(more_steps > 0);
  }
}

TEST_CASE("clouds past the small-cloud folds, the prefix sum over one work-group or many, equal the reference",
          "[device][kernels]") {
  if (!test::device_available()) return;
  // 40x30, so that the reference's 16,384 renderings a frame stay quick; the host rasterizer's atlas
  // (renderer cpu) leaves only the device's float arithmetic to differ. One particle more than
  // kFusedLaunchParticles: the summary, prefix sum and resampling as separate one-group launches;
  // kWideSummaryParticles: over many groups.
  const Scene scene = make_scene(3, 16);
  for (const size_t particles : {kFusedLaunchParticles + 1, kWideSummaryParticles}) {
    INFO(particles << " particles");
    TrackerConfig config;
    config.particles = static_cast<int>(particles);
    config.seed = 9;
    config.backend = test::device_selector();
    config.renderer = Renderer::Cpu;
    config.refine.enabled = false;
    each_frame_from_common_state(
        scene, config,
        [&](size_t f, const Estimate& a, const Estimate& b, reference::ReferenceFilter& reference,
            DeviceFilter& device) {
          CHECK(translation_error(a.pose, b.pose) <= 1e-5);
          CHECK(rotation_error(a.pose, b.pose) <= 1e-4);
          CHECK(b.effective_sample_size == Approx(a.effective_sample_size).epsilon(1e-3).margin(1e-3));
          REQUIRE(a.resampled == b.resampled);
          if (a.resampled) {
            // Ancestry from the prefix sum (one group or many): the reference's resampling of the device's own
            // likelihoods (with 16,384 children some points lie within the likelihoods' float rounding of a
            // boundary), but for children within the float log weights' rounding of one (log weights of
            // hundreds of nats carry ~3e-5 of it: 1-3 children a frame here, as many with one group at 16,383
            // particles). The prefix sum itself is held to exact ancestry on given weights (test_kernels.cpp).
            std::vector<double> w = reference.last_normalized_weights();
            const auto ll_ref = reference.last_log_likelihoods(),
                       ll_dev = DeviceFilterProbe(device).last_log_likelihoods();
            double sum = 0;
            for (size_t i = 0; i < w.size(); ++i) sum += w[i] *= std::exp(ll_dev[i] - ll_ref[i]);
            for (double& x : w) x /= sum;
            const double u =
                dt_uniform01(dt_random_words(config.seed, 0u, static_cast<dt_u32>(f), DT_STREAM_RESAMPLE, 0u).v[0]);
            const auto expected = reference::systematic_resample(w, u), got = DeviceFilterProbe(device).last_parents();
            size_t differing = 0;
            for (size_t i = 0; i < expected.size(); ++i) differing += expected[i] != got[i];
            CHECK(differing <= expected.size() / 1000);
          }
        });
  }
}

TEST_CASE("more particles than the device can hold is a clear error, not a crash, for every renderer",
          "[device][errors]") {
  if (!test::device_available()) return;
  for (const char* renderer : {"cpu", "gl", "kernel"}) {
    if (std::string(renderer) == "gl" && !gl_available()) continue;
    INFO("renderer " << renderer);
    TrackerConfig config;
    config.particles = 100'000'000;
    config.renderer = renderer_from_string(renderer);
    const Camera camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
    // The whole image's state: refused before anything is allocated, GL pages included.
    TrackerConfig whole = config;
    whole.occlusion_window = OcclusionWindow::whole_image();
    CHECK_THROWS_WITH(DeviceFilter(compute::open_device(test::device_selector()), builtin_demo_mesh(), camera, whole),
                      Catch::Contains("100000000 particles at 80x60 need") && Catch::Contains("GiB") &&
                          Catch::Contains("particles fit"));
    // The automatic window (the default) has no size before the start: refused at construction where
    // even the rest does not fit, else at the start, naming the window it sized.
    const auto build_and_start = [&] {
      DeviceFilter filter(compute::open_device(test::device_selector()), builtin_demo_mesh(), camera, config);
      filter.initialize(Pose({0, 0, 0.8}, Eigen::Quaterniond::Identity()), InitialSpread{0.01, 0.05});
    };
    CHECK_THROWS_WITH(build_and_start(), Catch::Contains("100000000 particles at 80x60") && Catch::Contains("GiB") &&
                                             Catch::Contains("particles fit"));
  }
}

TEST_CASE("the atlas' tiles: every particle's, at most atlas_particles and what one buffer holds", "[device][atlas]") {
  CHECK(kernel_atlas_tiles(30, 4800, 0, 0) == 30);
  CHECK(kernel_atlas_tiles(30, 4800, 7, 0) == 7);
  CHECK(kernel_atlas_tiles(30, 4800, 70, 0) == 30);
  // 30,000 particles at 640x480 on an H100's NVIDIA OpenCL (19.8 GiB in one buffer): 1,228,800 bytes a tile.
  CHECK(kernel_atlas_tiles(30000, 640 * 480, 0, 21254373376) == 17296);
  CHECK(kernel_atlas_tiles(5, 100, 0, 100) ==
        1);  // a buffer smaller than one tile: one tile, refused by its allocation
}

TEST_CASE("an atlas of fewer tiles than particles, drawn and weighed in turns, gives the same frames",
          "[device][kernel][atlas]") {
  if (!test::device_available()) return;
  // 160x120: the tile does not fit in work-group memory, so the kernel renderer draws a separate atlas.
  const Scene scene = make_scene(4, 4);
  TrackerConfig config;
  config.particles = 30;
  config.seed = 3;
  config.backend = test::device_selector();
  TrackerConfig turns = config;
  turns.atlas_particles = 7;  // four turns of 7 and one of 2
  DeviceFilter whole(compute::open_device(config.backend), scene.mesh, scene.working, config);
  DeviceFilter chunked(compute::open_device(config.backend), scene.mesh, scene.working, turns);
  const InitialSpread spread{0.01, 0.05};
  whole.initialize(scene.frames[0].ground_truth, spread);
  chunked.initialize(scene.frames[0].ground_truth, spread);
  for (size_t f = 0; f < scene.frames.size(); ++f) {
    INFO(scene.name << ", frame " << f);
    const double dt = frame_dt(scene, f);
    const Estimate a = whole.update(scene.frames[f].depth, dt);
    const Estimate b = chunked.update(scene.frames[f].depth, dt);
    // The same kernels on the same tiles, only launched in turns: the same numbers, bit for bit.
    CHECK(DeviceFilterProbe(whole).last_log_likelihoods() == DeviceFilterProbe(chunked).last_log_likelihoods());
    CHECK(DeviceFilterProbe(whole).last_parents() == DeviceFilterProbe(chunked).last_parents());
    CHECK(a.pose.translation == b.pose.translation);
    CHECK(a.pose.rotation.coeffs() == b.pose.rotation.coeffs());
    CHECK(a.refine_iterations == b.refine_iterations);
  }
  CHECK_THROWS_WITH(DeviceFilterProbe(chunked).last_atlas(), Catch::Contains("drawn in turns"));
  // And against the reference, as every layout is.
  each_frame_from_common_state(scene, turns, [&](size_t, const Estimate& a, const Estimate& b, auto&, auto&) {
    CHECK(translation_error(a.pose, b.pose) <= 1e-5);
    CHECK(rotation_error(a.pose, b.pose) <= 1e-4);
  });
}
