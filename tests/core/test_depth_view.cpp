// DepthView (a caller's buffer in place) against the DepthImage path it must equal, its input
// checks, caller timestamps, and Camera::from_matrix.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <depthtrack/depth_view.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/synth.hpp>
#include <depthtrack/tracker.hpp>
#include <limits>
#include <vector>

#include "same_estimate.hpp"
#include "synth_frames.hpp"

using namespace depthtrack;
using Catch::Matchers::Contains;

namespace {

constexpr double kMetresPerUnit = 1e-4;

// The synthetic frames as a sensor delivers them: uint16 units (0 = missing).
std::vector<uint16_t> to_units(const DepthImage& depth) {
  std::vector<uint16_t> units(depth.data().size(), 0);
  for (size_t i = 0; i < units.size(); ++i)
    if (DepthImage::is_valid(depth.data()[i]))
      units[i] = static_cast<uint16_t>(std::lround(depth.data()[i] / kMetresPerUnit));
  return units;
}

// Equal pixel for pixel, NaN where the other is NaN.
void require_same_image(const DepthImage& a, const DepthImage& b) {
  REQUIRE(a.width() == b.width());
  REQUIRE(a.height() == b.height());
  size_t differing = 0;
  for (size_t i = 0; i < a.data().size(); ++i) {
    const float x = a.data()[i], y = b.data()[i];
    differing += !((std::isnan(x) && std::isnan(y)) || x == y);
  }
  REQUIRE(differing == 0);
}

}  // namespace

TEST_CASE("DepthView converts float32 and uint16 pixels exactly as DepthImage does", "[depth_view]") {
  const int w = 7, h = 4;
  std::vector<float> metres(w * h);
  for (int i = 0; i < w * h; ++i) metres[i] = 0.5f + 0.01f * static_cast<float>(i);
  metres[3] = 0.0f;  // the sensors' three spellings of "missing"
  metres[9] = std::numeric_limits<float>::quiet_NaN();
  metres[15] = std::numeric_limits<float>::infinity();
  require_same_image(DepthView::metres(metres.data(), w, h).to_image(), DepthImage::from_metres(w, h, metres));

  std::vector<uint16_t> units(w * h);
  for (int i = 0; i < w * h; ++i) units[i] = static_cast<uint16_t>(i * 997 % 65536);
  const DepthImage from_units = DepthImage::from_units(w, h, units, 0.00025);
  require_same_image(DepthView::units(units.data(), w, h, 0.00025).to_image(), from_units);
  CHECK(std::isnan(from_units.at(0, 0)));                           // 0 = missing
  CHECK(from_units.at(1, 0) == static_cast<float>(997 * 0.00025));  // hand-computed

  // A negative depth is named by its pixel in both paths.
  metres[2 * w + 5] = -0.25f;
  CHECK_THROWS_WITH(DepthView::metres(metres.data(), w, h).to_image(), Contains("pixel (5, 2)"));
  CHECK_THROWS_WITH(DepthImage::from_metres(w, h, metres), Contains("pixel (5, 2)"));
}

TEST_CASE("DepthView reads a sub-rectangle of a larger image through its row stride", "[depth_view]") {
  const int w = 6, h = 4, big_w = 11, big_h = 9, x0 = 3, y0 = 2;
  std::vector<float> big(big_w * big_h, -1.0f);  // negative outside the window: read there, it would throw
  std::vector<float> window(w * h);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) window[v * w + u] = big[(y0 + v) * big_w + x0 + u] = 1.0f + 0.1f * (v * w + u);
  const DepthView view = DepthView::metres(&big[y0 * big_w + x0], w, h, big_w * sizeof(float));
  require_same_image(view.to_image(), DepthImage::from_metres(w, h, window));
  // Decimated: every second pixel of every second row, as DepthImage::decimated.
  require_same_image(view.sample(2), DepthImage::from_metres(w, h, window).decimated(2));
  // max_depth: deeper pixels become missing.
  const DepthImage clipped = view.sample(1, 1.45f);
  CHECK(clipped.at(4, 0) == 1.4f);
  CHECK(std::isnan(clipped.at(5, 0)));
}

TEST_CASE("A tracker fed DepthViews gives the DepthImage path's estimates: float32, uint16, strided",
          "[depth_view][tracker]") {
  const Mesh mesh = builtin_demo_mesh();
  const SynthConfig synth = test::small_scene(8, 4);
  const std::vector<SynthFrame> frames = test::synthesize(mesh, synth);
  TrackerConfig config;  // reference, 80x60, seed 1
  config.particles = 60;
  const int w = synth.camera.width, h = synth.camera.height;
  Tracker by_image(mesh, synth.camera, config), by_units(mesh, synth.camera, config),
      by_metres(mesh, synth.camera, config), by_window(mesh, synth.camera, config);
  for (Tracker* t : {&by_image, &by_units, &by_metres, &by_window}) t->initialize(frames[0].ground_truth);
  // The strided case: each frame as the bottom-right part of a wider, taller buffer.
  const int pad_u = 5, pad_v = 3, big_w = w + pad_u + 2;
  std::vector<float> big(static_cast<size_t>(big_w) * (h + pad_v), std::numeric_limits<float>::quiet_NaN());
  for (const SynthFrame& f : frames) {
    const std::vector<uint16_t> units = to_units(f.depth);
    const DepthImage image = DepthImage::from_units(w, h, units, kMetresPerUnit);
    std::vector<float> metres = image.data();
    for (float& z : metres)
      if (std::isnan(z)) z = 0.0f;  // missing as a driver writes it
    for (int v = 0; v < h; ++v)
      std::memcpy(&big[static_cast<size_t>(v + pad_v) * big_w + pad_u], &metres[static_cast<size_t>(v) * w],
                  w * sizeof(float));
    const Estimate expected = by_image.update(image, f.timestamp);
    test::require_same_estimate(by_units.update(DepthView::units(units.data(), w, h, kMetresPerUnit), f.timestamp),
                                expected);
    test::require_same_estimate(by_metres.update(DepthView::metres(metres.data(), w, h), f.timestamp), expected);
    const DepthView window = DepthView::metres(&big[static_cast<size_t>(pad_v) * big_w + pad_u], w, h,
                                               static_cast<size_t>(big_w) * sizeof(float));
    test::require_same_estimate(by_window.update(window, f.timestamp), expected);
  }
}

TEST_CASE("initialize_global from a DepthView equals the DepthImage path", "[depth_view][tracker]") {
  const Mesh mesh = builtin_demo_mesh();
  const SynthConfig synth = test::small_scene(1, 4);
  const SynthFrame f = test::synthesize(mesh, synth).front();
  const std::vector<uint16_t> units = to_units(f.depth);
  const int w = synth.camera.width, h = synth.camera.height;
  TrackerConfig config;
  config.particles = 60;
  Tracker a(mesh, synth.camera, config), b(mesh, synth.camera, config);
  const InitHint box = InitHint::box(40, 25, 120, 95);
  const Estimate expected = a.initialize_global(DepthImage::from_units(w, h, units, kMetresPerUnit), 0.0, box);
  test::require_same_estimate(b.initialize_global(DepthView::units(units.data(), w, h, kMetresPerUnit), 0.0, box),
                              expected);
  CHECK(translation_error(expected.pose, f.ground_truth) < 0.02);
}

TEST_CASE("Bad DepthViews and timestamps are InputErrors naming the problem", "[depth_view][tracker]") {
  const Mesh mesh = builtin_demo_mesh();
  const Camera camera = Camera::make(80, 60, 66, 66, 39.5, 29.5);
  TrackerConfig config;
  config.particles = 20;
  Tracker tracker(mesh, camera, config);
  tracker.initialize(Pose({0, 0, 0.8}, Eigen::Quaterniond::Identity()));
  std::vector<uint16_t> units(80 * 60, 8000);
  std::vector<float> metres(80 * 60, 0.8f);
  CHECK_THROWS_AS(tracker.update(DepthView::units(nullptr, 80, 60, 1e-4), 0.0), InputError);
  CHECK_THROWS_WITH(tracker.update(DepthView::units(nullptr, 80, 60, 1e-4), 0.0), Contains("pointer is null"));
  CHECK_THROWS_WITH(tracker.update(DepthView::metres(metres.data(), 80, 60, 79 * sizeof(float)), 0.0),
                    Contains("row stride 316 bytes is less than a row of 80 float32 metres pixels (320 bytes)"));
  CHECK_THROWS_WITH(tracker.update(DepthView::metres(metres.data(), 40, 60), 0.0),
                    Contains("depth view is 40x60 but the camera is 80x60"));
  CHECK_THROWS_WITH(tracker.update(DepthView::units(units.data(), 80, 60, 0.0), 0.0),
                    Contains("metres_per_unit must be finite and positive"));
  CHECK_THROWS_WITH(tracker.update(DepthView::units(units.data(), 80, 60, -1e-3), 0.0), Contains("metres_per_unit"));
  CHECK_THROWS_WITH(tracker.update(DepthView::units(units.data(), 80, 60, std::nan("")), 0.0),
                    Contains("metres_per_unit"));
  CHECK_THROWS_WITH(tracker.update(DepthView::metres(metres.data(), 0, 60), 0.0), Contains("size 0x60 is invalid"));
  // Caller timestamps: seconds, increasing, finite.
  const DepthView good = DepthView::units(units.data(), 80, 60, 1e-4);
  CHECK_THROWS_WITH(tracker.update(good, std::nan("")), Contains("timestamp is not finite"));
  tracker.update(good, 10.0);
  CHECK_THROWS_WITH(tracker.update(good, 10.0), Contains("timestamps must increase: 10 s follows 10 s"));
  CHECK_THROWS_WITH(tracker.update(good, 9.5), Contains("timestamps must increase"));
  CHECK_NOTHROW(tracker.update(good, 10.033));
  // Nanoseconds are a unit mistake; Unix-epoch seconds are real times.
  CHECK_THROWS_WITH(tracker.update(good, 1.7e18), Contains("outside the sane range"));
  CHECK_NOTHROW(tracker.update(good, 1.7e9));
}

TEST_CASE("Camera::from_matrix reads K and rejects skew and impossible intrinsics", "[camera]") {
  Eigen::Matrix3d K;
  K << 525, 0, 319.5, 0, 520, 239.5, 0, 0, 1;
  const Camera c = Camera::from_matrix(640, 480, K);
  CHECK(c.width == 640);
  CHECK(c.height == 480);
  CHECK(c.fx == 525);
  CHECK(c.fy == 520);
  CHECK(c.cx == 319.5);
  CHECK(c.cy == 239.5);
  CHECK(c.matrix() == K);
  Eigen::Matrix3d skew = K;
  skew(0, 1) = 0.5;
  CHECK_THROWS_WITH(Camera::from_matrix(640, 480, skew), Contains("skew K[0][1] = 0.5"));
  Eigen::Matrix3d lower = K;
  lower(2, 0) = 1e-3;
  CHECK_THROWS_WITH(Camera::from_matrix(640, 480, lower), Contains("upper triangular"));
  Eigen::Matrix3d scaled = 2 * K;
  CHECK_THROWS_WITH(Camera::from_matrix(640, 480, scaled), Contains("row 0 0 1"));
  Eigen::Matrix3d negative = K;
  negative(1, 1) = -520;
  CHECK_THROWS_WITH(Camera::from_matrix(640, 480, negative), Contains("fy = -520"));
  Eigen::Matrix3d off_centre = K;
  off_centre(0, 2) = 2000;  // far outside a 640-wide image
  CHECK_THROWS_WITH(Camera::from_matrix(640, 480, off_centre), Contains("principal point"));
  Eigen::Matrix3d nan = K;
  nan(0, 0) = std::nan("");
  CHECK_THROWS_WITH(Camera::from_matrix(640, 480, nan), Contains("non-finite"));
  CHECK_THROWS_AS(Camera::from_matrix(0, 480, K), InputError);
}

TEST_CASE("While lost a DepthView-fed tracker searches the whole view", "[depth_view][tracker]") {
  const Mesh mesh = builtin_demo_mesh();
  SynthConfig synth = test::small_scene(24, 4);
  synth.occluder_fraction = 0;
  synth.hidden_from = 0.3;  // frames 9-23: only the wall
  synth.hidden_until = 10.0;
  const std::vector<SynthFrame> frames = test::synthesize(mesh, synth);
  TrackerConfig config;
  config.particles = 40;
  config.recovery.budget_ms = 20;
  Tracker tracker(mesh, synth.camera, config);
  tracker.initialize(frames[0].ground_truth);
  size_t searched = 0;
  bool lost = false;
  for (const SynthFrame& f : frames) {
    const std::vector<uint16_t> units = to_units(f.depth);
    const Estimate e = tracker.update(
        DepthView::units(units.data(), synth.camera.width, synth.camera.height, kMetresPerUnit), f.timestamp);
    lost = lost || e.status == TrackStatus::Lost;
    searched += e.search_poses;
    if (!f.hidden) CHECK(e.search_poses == 0);
  }
  CHECK(lost);
  CHECK(searched > 0);  // the search ran on the view converted whole
}
