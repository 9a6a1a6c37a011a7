// Bad input to the Tracker: each is an InputError that names the problem.
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/tracker.hpp>

#include "scene.hpp"

using namespace depthtrack;

namespace {
const Camera sensor = Camera::make(160, 120, 131.25, 131.25, 79.875, 59.875);
const Pose truth({0.0, 0.0, 0.8}, Eigen::Quaterniond::Identity());
}  // namespace

TEST_CASE("zero particles is refused", "[errors]") {
  TrackerConfig c;
  c.particles = 0;
  CHECK_THROWS_WITH(Tracker(builtin_demo_mesh(), sensor, c), Catch::Contains("particle count 0"));
}

TEST_CASE("an unknown backend lists the available ones", "[errors]") {
  TrackerConfig c;
  c.backend = "vulkan";
  CHECK_THROWS_WITH(Tracker(builtin_demo_mesh(), sensor, c),
                    Catch::Contains("unknown backend 'vulkan'") && Catch::Contains("reference"));
}

TEST_CASE("a working resolution that does not divide the sensor's is refused", "[errors]") {
  TrackerConfig c;
  c.width = 70;
  c.height = 60;
  CHECK_THROWS_WITH(Tracker(builtin_demo_mesh(), sensor, c), Catch::Contains("70x60"));
}

TEST_CASE("an empty mesh is refused", "[errors]") {
  CHECK_THROWS_WITH(Tracker(Mesh{}, sensor, TrackerConfig{}), Catch::Contains("empty"));
}

TEST_CASE("update checks order, image size and timestamps", "[errors]") {
  Tracker tracker(builtin_demo_mesh(), sensor, TrackerConfig{});
  const DepthImage good = test::render_scene(builtin_demo_mesh(), sensor, truth);
  CHECK_THROWS_WITH(tracker.update(good, 0.0), Catch::Contains("before initialize"));
  tracker.initialize(truth);
  CHECK_THROWS_WITH(tracker.update(DepthImage(80, 60), 0.0), Catch::Contains("80x60") && Catch::Contains("160x120"));
  tracker.update(good, 1.0);
  CHECK_THROWS_WITH(tracker.update(good, 0.5), Catch::Contains("timestamps must increase"));
  CHECK_THROWS_WITH(tracker.update(good, 1.0), Catch::Contains("timestamps must increase"));
  CHECK_THROWS_WITH(tracker.update(good, NAN), Catch::Contains("not finite"));
  // A refused frame leaves the tracker usable.
  CHECK_NOTHROW(tracker.update(good, 1.0 + 1.0 / 30));
}
