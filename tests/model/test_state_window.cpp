// The occlusion state window (TrackerConfig::occlusion_window, model::StateWindow): where it lies, and
// what the reference filter does with pixels inside and outside it, against independent statements.
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/tracker.hpp>
#include <set>

#include "model/occlusion_chain.hpp"
#include "model/state_window.hpp"
#include "reference/observation_model.hpp"
#include "reference/rasterizer.hpp"
#include "reference/reference_filter.hpp"
#include "scene.hpp"
#include "synth_frames.hpp"

using namespace depthtrack;

namespace {
const Camera camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);

TrackerConfig window_config(OcclusionStorage mode, int width, int height) {
  TrackerConfig c;
  c.particles = 40;
  c.occlusion_storage = mode;
  c.seed = 5;
  c.occlusion_window = width == 0 && height == 0 ? OcclusionWindow::whole_image() : OcclusionWindow{width, height};
  return c;
}

// Runs `windowed` and `whole` (the whole image's state) over the frames, both started at the first
// frame's truth, and requires the same log-likelihoods and estimates and, inside each frame's window,
// the same state bit for bit. Returns the windows `windowed` kept, frame by frame.
std::vector<model::StateWindow> run_against_whole_image(reference::ReferenceFilter& windowed,
                                                        reference::ReferenceFilter& whole,
                                                        const std::vector<SynthFrame>& frames, const Camera& image,
                                                        size_t particles) {
  whole.initialize(frames[0].ground_truth, InitialSpread{0.01, 0.05});
  windowed.initialize(frames[0].ground_truth, InitialSpread{0.01, 0.05});
  std::vector<model::StateWindow> windows{windowed.state_window()};
  for (size_t f = 0; f < frames.size(); ++f) {
    INFO("frame " << f);
    const double dt = f == 0 ? 0.0 : frames[f].timestamp - frames[f - 1].timestamp;
    const Estimate a = whole.update(frames[f].depth, dt), b = windowed.update(frames[f].depth, dt);
    REQUIRE(whole.last_log_likelihoods() == windowed.last_log_likelihoods());
    REQUIRE(a.pose.translation == b.pose.translation);
    REQUIRE(a.pose.rotation.coeffs() == b.pose.rotation.coeffs());
    const model::StateWindow w = windowed.state_window();
    windows.push_back(w);
    const size_t pixels = static_cast<size_t>(image.pixel_count());
    REQUIRE(windowed.occlusion_state().size() == particles * w.pixels());
    for (size_t i = 0; i < particles; ++i)
      for (int v = w.v0; v < w.v0 + w.height; ++v)
        for (int u = w.u0; u < w.u0 + w.width; ++u) {
          const size_t k = static_cast<size_t>(v * image.width + u), j = i * w.pixels() + w.index(u, v);
          REQUIRE(windowed.occlusion_state()[j] == whole.occlusion_state()[i * pixels + k]);
          REQUIRE(windowed.occlusion_times()[j] == whole.occlusion_times()[i * pixels + k]);
        }
  }
  return windows;
}
}  // namespace

TEST_CASE("the state window is the configured size, centred on the projected mesh centre, inside the image",
          "[window]") {
  CHECK(model::state_window_size(window_config(OcclusionStorage::PerPixelTime, 0, 0), camera) ==
        model::StateWindow{0, 0, 80, 60});
  CHECK(model::state_window_size(window_config(OcclusionStorage::PerPixelTime, 100, 7), camera) ==
        model::StateWindow{0, 0, 80, 7});
  const model::StateWindow w = model::state_window_size(window_config(OcclusionStorage::PerPixelTime, 20, 10), camera);
  CHECK(w.pixels() == 200);
  const Eigen::Vector3d centre(0.01, -0.02, 0.03);  // object frame
  auto at = [&](const Eigen::Vector3d& point_in_camera) {
    // A pose that puts the mesh centre at point_in_camera (rotated: the centre is turned with it).
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Eigen::Vector3d(0, 1, 1).normalized()));
    return model::state_window_at(w, Pose(point_in_camera - q * centre, q), centre, camera);
  };
  // On the optical axis: the projection (39.9375, 29.9375) is nearest pixel (40, 30); the 20x10 window
  // starts 10 and 5 pixels before it.
  CHECK(at({0, 0, 0.8}) == model::StateWindow{30, 25, 20, 10});
  // u = 65.625 * 0.2 / 0.8 + 39.9375 = 56.34 -> 56; v = 65.625 * -0.1 / 0.8 + 29.9375 = 21.73 -> 22.
  CHECK(at({0.2, -0.1, 0.8}) == model::StateWindow{46, 17, 20, 10});
  // Near the edges, and far beyond them: clamped inside the image.
  CHECK(at({-0.6, -0.45, 0.8}) == model::StateWindow{0, 0, 20, 10});
  CHECK(at({1e9, 1e9, 0.8}) == model::StateWindow{60, 50, 20, 10});
  // Behind the camera or not finite: where it was.
  const model::StateWindow placed = at({0.2, -0.1, 0.8});
  CHECK(model::state_window_at(placed, Pose({0, 0, -1}, Eigen::Quaterniond::Identity()), Eigen::Vector3d::Zero(),
                               camera) == placed);
  CHECK(model::state_window_at(placed, Pose({NAN, 0, 1}, Eigen::Quaterniond::Identity()), Eigen::Vector3d::Zero(),
                               camera) == placed);
  // A negative size is refused by name.
  CHECK_THROWS_WITH(window_config(OcclusionStorage::PerPixelTime, -1, 5).validate(),
                    Catch::Contains("occlusion window -1x5"));
  // The command lines' spelling (track and depthtrack_bench): auto, full or WxH.
  CHECK(occlusion_window_from_string("auto").is_automatic());
  const OcclusionWindow full = occlusion_window_from_string("full");
  CHECK((!full.is_automatic() && full.width == 0 && full.height == 0));
  const OcclusionWindow fixed = occlusion_window_from_string("24x16");
  CHECK((!fixed.is_automatic() && fixed.width == 24 && fixed.height == 16));
  for (const char* bad : {"32", "32x-4", "wide", "24x16x2", ""})
    CHECK_THROWS_WITH(occlusion_window_from_string(bad), Catch::Contains("is not auto, full or WxH"));
}

// Per-pixel time: a pixel outside every window the filter had holds the fresh state (0.1 at time 0) in
// the whole-image filter too, so a window that holds every pixel the particles ever cover changes
// nothing: the same log-likelihoods and estimates bit for bit, and its rows are the whole image's
// state cut to the window.
TEST_CASE("a state window that holds every covered pixel gives the whole-image filter's results", "[window][filter]") {
  const Mesh mesh = builtin_demo_mesh();
  SynthConfig synth = test::small_scene(12);
  const auto frames = test::synthesize(mesh, synth);
  TrackerConfig whole_config = window_config(OcclusionStorage::PerPixelTime, 0, 0), cut_config = whole_config;
  cut_config.occlusion_window = {60, 44};
  reference::ReferenceFilter whole(mesh, synth.camera, whole_config), cut(mesh, synth.camera, cut_config);
  std::set<std::pair<int, int>> origins;
  for (const model::StateWindow& w :
       run_against_whole_image(cut, whole, frames, synth.camera, static_cast<size_t>(whole_config.particles)))
    origins.insert({w.u0, w.v0});
  CHECK(origins.size() >= 2);  // the window followed the estimate
}

// A window that cuts the object: frame 2's log-likelihood of each particle is the sum over its covered
// pixels with the prior from its frame-1 row where both windows hold the pixel, and the fresh prior
// (0.1 aged from time 0) elsewhere; its new row holds each covered pixel's posterior.
TEST_CASE("pixels outside the state window are weighed with a fresh prior and keep no state", "[window][filter]") {
  const Mesh mesh = builtin_demo_mesh();
  const Pose truth({0.0, 0.0, 0.8}, Eigen::Quaterniond(Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 1, 0).normalized())));
  DepthImage depth = test::render_scene(mesh, camera, truth);
  for (int v = 0; v < 60; ++v)
    for (int u = 36; u < 42; ++u) depth.at(u, v) = 0.6f;  // an occluding bar across the object
  for (const OcclusionStorage mode : {OcclusionStorage::PerPixelTime, OcclusionStorage::GlobalTime}) {
    INFO(to_string(mode));
    TrackerConfig config = window_config(mode, 12, 8);
    config.refine.enabled = false;
    config.resample_kl_threshold = 1e9;                            // never resamples: rows stay each particle's
    config.motion.sigma_linear = config.motion.sigma_angular = 0;  // and poses stay put
    reference::ReferenceFilter filter(mesh, camera, config);
    filter.initialize(truth, InitialSpread{0.004, 0.02});
    filter.update(depth, 0.0);
    const model::StateWindow first = filter.state_window();
    const std::vector<float> p1 = filter.occlusion_state(), t1 = filter.occlusion_times();
    const double dt = 0.25;
    filter.update(depth, dt);
    const model::StateWindow second = filter.state_window();
    const std::vector<float> p2 = filter.occlusion_state();
    const double now = dt;
    const OcclusionModel chain;
    const double fresh = model::propagate_occlusion(chain, chain.initial, now);
    reference::Rasterizer r(mesh, camera, config.near_plane, config.observation.max_depth);
    std::vector<float> rendered(static_cast<size_t>(camera.pixel_count()));
    size_t outside = 0, inside = 0;
    for (size_t i = 0; i < static_cast<size_t>(config.particles); ++i) {
      r.render(filter.particles()[i].pose, rendered);
      double expected = 0;
      for (int v = 0; v < 60; ++v)
        for (int u = 0; u < 80; ++u) {
          const float y_hat = rendered[static_cast<size_t>(v * 80 + u)], y = depth.at(u, v);
          if (y_hat <= 0 || !DepthImage::is_valid(y)) continue;
          double p = fresh;
          if (second.contains(u, v) && first.contains(u, v)) {
            const size_t j = i * first.pixels() + first.index(u, v);
            p = mode == OcclusionStorage::PerPixelTime ? model::propagate_occlusion(chain, p1[j], now - t1[j])
                                                       : model::propagate_occlusion(chain, p1[j], dt);
          }
          const auto d = reference::pixel_densities(ObservationModel{}, y, y_hat);
          expected += reference::pixel_log_ratio(d, p);
          if (!second.contains(u, v)) {
            ++outside;
            continue;
          }
          ++inside;
          REQUIRE(p2[i * second.pixels() + second.index(u, v)] ==
                  Approx(reference::occlusion_posterior(d, p)).epsilon(1e-6));
        }
      // Global time ages the stored floats in place (float rounding), per-pixel time only reads them.
      REQUIRE(filter.last_log_likelihoods()[i] ==
              Approx(expected).epsilon(mode == OcclusionStorage::GlobalTime ? 1e-7 : 1e-12));
    }
    CHECK(p2.size() == static_cast<size_t>(config.particles) * 96);
    CHECK(outside > 20 * static_cast<size_t>(config.particles));  // the window cuts every particle's silhouette
    CHECK(inside > 20 * static_cast<size_t>(config.particles));
  }
}

// The automatic window by hand: a 10 cm cube, axis-aligned, centred on the optical axis. At 0.8 m its
// nearer corners (z = 0.75) project 65.625 * 0.05 / 0.75 = 4.375 pixels from the centre's projection;
// with a fifth more, 2 pixels and the half pixel to the centre's nearest pixel that reaches 7.75, so 8
// pixels each side: 17 x 17 from (40 - 8, 30 - 8).
TEST_CASE("the automatic window holds the projected box with its margins and grows with it", "[window]") {
  const Mesh cube = make_box({0.1f, 0.1f, 0.1f});
  const model::ObjectExtent extent = model::object_extent(cube);
  TrackerConfig automatic;
  CHECK(automatic.occlusion_window.is_automatic());  // the default
  CHECK(model::state_window_size(automatic, camera).pixels() == 0);  // sized at the start
  const auto at = [](double z) { return Pose({0, 0, z}, Eigen::Quaterniond::Identity()); };
  const model::StateWindow start = model::start_state_window(automatic, extent, at(0.8), camera);
  CHECK(start == model::StateWindow{32, 22, 17, 17});
  // Twice as near (0.4 m): 65.625 * 0.05 / 0.35 = 9.375 -> 9.375 * 1.2 + 2.5 = 13.75: 14 a side, 29 x 29.
  const model::StateWindow near = model::next_state_window(start, automatic, extent, at(0.4), camera, 0);
  CHECK(near == model::StateWindow{26, 16, 29, 29});
  // Farther again: it does not shrink (until the next start).
  CHECK(model::next_state_window(near, automatic, extent, at(1.6), camera, 0) == near);
  // Growth beyond the memory's bound is refused: the window stays as it was, placed at the estimate.
  CHECK(model::next_state_window(start, automatic, extent, at(0.4), camera, 400) == start);
  // A corner behind the camera plane: the projection is unbounded, the whole image.
  CHECK(model::start_state_window(automatic, extent, at(0.03), camera) == model::StateWindow{0, 0, 80, 60});
  // The centre behind the camera, or a non-finite pose, says nothing: unchanged.
  CHECK(model::next_state_window(start, automatic, extent, at(-1.0), camera, 0) == start);
  CHECK(model::next_state_window(start, automatic, extent, at(NAN), camera, 0) == start);
  // A fixed window never grows; a turned cube reaches farther (its diagonal).
  const TrackerConfig fixed = window_config(OcclusionStorage::PerPixelTime, 17, 17);
  CHECK(model::next_state_window(start, fixed, extent, at(0.4), camera, 0) == start);
  const Pose turned({0, 0, 0.8}, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ())));
  CHECK(model::start_state_window(automatic, extent, turned, camera).width > 17);
}

// An object coming from 1.15 m to 0.55 m: the automatic window starts well inside the image and grows
// with it, and holds every pixel the particles cover, so it keeps the whole-image filter's numbers bit
// for bit (as the fixed window above).
TEST_CASE("an automatic window follows an approaching object and gives the whole-image filter's results",
          "[window][filter]") {
  const Mesh mesh = builtin_demo_mesh();
  SynthConfig synth = test::small_scene(72);
  // z = 0.8 + 0.35 sin(2 pi 1.7 t / 8 + 3.9) (synth/trajectory.cpp): farthest, 1.15 m, at frame 18,
  // then in to 0.55 m by frame 71 (at most 1.6 cm a frame).
  synth.trajectory.amplitude = {0.02, 0.01, -0.35};
  synth.trajectory.period = 8.0;
  synth.occluder_fraction = 0;  // tracked closely, so that the window follows the object in
  synth.sensor.kind = SensorKind::Ideal;
  auto frames = test::synthesize(mesh, synth);
  frames.erase(frames.begin(), frames.begin() + 18);
  TrackerConfig whole_config = window_config(OcclusionStorage::PerPixelTime, 0, 0), auto_config = whole_config;
  auto_config.occlusion_window = OcclusionWindow{};
  reference::ReferenceFilter whole(mesh, synth.camera, whole_config), automatic(mesh, synth.camera, auto_config);
  const std::vector<model::StateWindow> windows =
      run_against_whole_image(automatic, whole, frames, synth.camera, static_cast<size_t>(whole_config.particles));
  const size_t first_size = windows.front().pixels();
  CHECK(first_size < static_cast<size_t>(synth.camera.pixel_count()) / 4);
  std::set<size_t> sizes;
  for (const model::StateWindow& w : windows) sizes.insert(w.pixels());
  CHECK(sizes.size() >= 3);  // it grew, more than once (21x17 to 27x23 here)
  CHECK(*sizes.rbegin() > 3 * first_size / 2);
}

// What a Tracker reports of its window: the automatic one sized at the start, the whole image with
// `full`, a fixed one as given (the reference's and the device's: Tracker::occlusion_window_size).
TEST_CASE("a tracker reports the occlusion state window it keeps", "[window][tracker]") {
  const Mesh cube = make_box({0.1f, 0.1f, 0.1f});
  const Pose at({0, 0, 0.8}, Eigen::Quaterniond::Identity());
  for (const auto& [window, expected] : {std::pair{OcclusionWindow{}, std::pair{17, 17}},
                                         std::pair{OcclusionWindow::whole_image(), std::pair{80, 60}},
                                         std::pair{OcclusionWindow::fixed(20, 10), std::pair{20, 10}}}) {
    TrackerConfig config;
    config.particles = 10;
    config.occlusion_window = window;
    Tracker tracker(cube, camera, config);
    tracker.initialize(at);
    CHECK(tracker.occlusion_window_size() == expected);
  }
}
