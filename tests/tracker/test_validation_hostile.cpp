// Input that used to be accepted silently and then gave garbage with exit 0: each is now
// refused with an error naming the problem, or handled (a huge time gap is capped).
#include <catch2/catch.hpp>
#include <chrono>
#include <depthtrack/error.hpp>
#include <depthtrack/sequence.hpp>
#include <depthtrack/tracker.hpp>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "scene.hpp"
#include "support.hpp"

using namespace depthtrack;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

const Camera sensor = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
const Pose truth({0.0, 0.0, 0.8}, Eigen::Quaterniond::Identity());

TrackerConfig small_config() {
  TrackerConfig c;
  c.particles = 50;
  return c;
}

// A YCB-Video clip folder with one 8x6 depth PNG and the given gt.json frames.
fs::path ycb_clip(const std::string& name, const nlohmann::json& frames) {
  const auto dir = test::temp_dir(name);
  DepthImage(8, 6).save_png(dir / "000001-depth.png", 0.0001);
  std::ofstream(dir / "gt.json") << nlohmann::json{{"frames", frames}}.dump(1);
  return dir;
}

nlohmann::json ycb_frame(const nlohmann::json& number, const nlohmann::json& objects) {
  const nlohmann::json k = {{10.0, 0, 4.0}, {0, 10.0, 3.0}, {0, 0, 1}};
  return {{"frame", number}, {"depth", "000001-depth.png"}, {"factor_depth", 10000}, {"K", k}, {"objects", objects}};
}

nlohmann::json ycb_object(const std::string& name) {
  return {{"name", name}, {"T_cam_obj", {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0.8}}}};
}

}  // namespace

TEST_CASE("an initial spread beyond sane bounds is refused", "[tracker][robustness]") {
  Tracker tracker(builtin_demo_mesh(), sensor, small_config());
  CHECK_THROWS_WITH(tracker.initialize(truth, InitialSpread{1e300, 1e300}), Contains("initial spread"));
  CHECK_THROWS_WITH(tracker.initialize(truth, InitialSpread{0.01, 7.0}), Contains("full turn"));
  CHECK_THROWS_WITH(tracker.initialize(truth, InitialSpread{-0.01, 0.1}), Contains("non-negative"));
  CHECK_NOTHROW(tracker.initialize(truth, InitialSpread{0.05, 3.0}));
}

TEST_CASE("a zero quaternion is refused; any other is normalized", "[tracker][robustness]") {
  Tracker tracker(builtin_demo_mesh(), sensor, small_config());
  Pose zero = truth;
  zero.rotation = Eigen::Quaterniond(0, 0, 0, 0);
  CHECK_THROWS_WITH(tracker.initialize(zero), Contains("zero quaternion"));
  Pose scaled = truth;
  scaled.rotation = Eigen::Quaterniond(2, 0, 0, 0);  // the identity, not normalized
  tracker.initialize(scaled, InitialSpread{0, 0});
  const Estimate e = tracker.update(test::render_scene(builtin_demo_mesh(), sensor, truth), 0.0);
  CHECK(e.pose.rotation.norm() == Approx(1.0).epsilon(1e-6));
  CHECK(e.pose.rotation.angularDistance(Eigen::Quaterniond::Identity()) < 1e-3);
}

TEST_CASE("a start behind the camera or beyond max depth is refused", "[tracker][robustness]") {
  Tracker tracker(builtin_demo_mesh(), sensor, small_config());
  CHECK_THROWS_WITH(tracker.initialize(Pose({0, 0, -0.8}, Eigen::Quaterniond::Identity())),
                    Contains("behind") && Contains("z = -0.8"));
  CHECK_THROWS_WITH(tracker.initialize(Pose({0, 0, 1e6}, Eigen::Quaterniond::Identity())),
                    Contains("beyond max depth"));
  CHECK_NOTHROW(tracker.initialize(Pose({0.3, 0, 2.0}, Eigen::Quaterniond::Identity())));
}

TEST_CASE("intrinsics that put the principal point far outside the image are refused", "[robustness]") {
  CHECK_THROWS_WITH(Camera::make(640, 480, 525, 525, 1e9, 240), Contains("principal point") && Contains("640x480"));
  CHECK_THROWS_WITH(Camera::make(640, 480, 525, 525, 320, -400), Contains("principal point"));
  CHECK_NOTHROW(Camera::make(640, 480, 525, 525, 700, -100));  // off-centre, but near
}

TEST_CASE("a huge gap between timestamps is propagated as max_time_step, not spread over kilometres",
          "[tracker][robustness]") {
  Tracker tracker(builtin_demo_mesh(), sensor, small_config());
  tracker.initialize(truth);
  const DepthImage scene = test::render_scene(builtin_demo_mesh(), sensor, truth);
  tracker.update(scene, 0.0);
  const Estimate after_gap = tracker.update(DepthImage(80, 60), 1e6);  // a dropout after a long pause
  CHECK(after_gap.status == TrackStatus::NoData);
  // One second of motion noise at most (tens of centimetres), not 11 km.
  CHECK((after_gap.pose.translation - truth.translation).norm() < 0.5);
}

TEST_CASE("the reference filter checks its memory before allocating", "[tracker][robustness]") {
  TrackerConfig c;
  c.particles = 2'000'000'000;
  CHECK_THROWS_WITH(Tracker(builtin_demo_mesh(), sensor, c), Contains("GiB of memory") && Contains("particles fit"));
}

TEST_CASE("gt.json: an object named twice in a frame, and frame numbers beyond nine digits, are errors",
          "[io][robustness]") {
  const auto twice = ycb_clip(
      "gt_twice", nlohmann::json::array(
                      {ycb_frame("000001", nlohmann::json::array({ycb_object("025_mug"), ycb_object("025_mug")}))}));
  CHECK_THROWS_WITH(load_sequence(twice), Contains("repeats object '025_mug'") && Contains("gt.json"));
  const auto near_max =
      ycb_clip("gt_int_max", nlohmann::json::array({ycb_frame(-2147483647, nlohmann::json::array({ycb_object("m")})),
                                                    ycb_frame(2147483647, nlohmann::json::array({ycb_object("m")}))}));
  CHECK_THROWS_WITH(load_sequence(near_max), Contains("frame number from 0 to 999999999"));
  const auto unsigned_huge =
      ycb_clip("gt_unsigned",
               nlohmann::json::array({ycb_frame(18446744073709551615ull, nlohmann::json::array({ycb_object("m")}))}));
  CHECK_THROWS_WITH(load_sequence(unsigned_huge), Contains("out of range"));
}

TEST_CASE("a depth PNG of the wrong size is refused from its header, before decoding", "[io][robustness]") {
  const auto dir = test::write_cli_sequence("png_header_first", 2);
  // A valid 16-bit PNG header claiming 8192x8192 over two rows of data: decoding would take 128 MiB
  // (16384x16384 is beyond the reader's limit altogether) only to find the rows missing.
  DepthImage big(8192, 2);
  big.save_png(dir / "seq" / "depth_000001.png", 0.001);
  {
    std::fstream f(dir / "seq" / "depth_000001.png", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(20);  // IHDR height, big-endian (the CRC is now wrong, but the size check comes first)
    const char height[4] = {0, 0, 0x20, 0};
    f.write(height, 4);
  }
  const Sequence s = load_sequence(dir / "seq");
  const auto start = std::chrono::steady_clock::now();
  CHECK_THROWS_WITH(s.load_depth(1), Contains("depth_000001.png"));
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 1.0);
}
