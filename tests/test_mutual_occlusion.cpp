// Mutual occlusion: which pixels one object's estimate hides from another (hand-placed boxes), and the
// MultiTracker's refusals.
#include <catch2/catch.hpp>
#include <cmath>
#include <depthtrack/error.hpp>
#include <depthtrack/multi_tracker.hpp>

#include "reference/rasterizer.hpp"
#include "tracker/mutual_occlusion.hpp"

using namespace depthtrack;
using Catch::Matchers::Contains;

TEST_CASE("Mutual occlusion hides the nearer box's pixels from the farther one, not the reverse", "[multi]") {
  const Camera sensor = Camera::make(160, 120, 131.25, 131.25, 79.875, 59.875);
  const Camera working = sensor.decimated(2);
  const std::vector<Mesh> boxes = {make_box({0.1f, 0.1f, 0.1f}), make_box({0.1f, 0.1f, 0.1f})};
  // Box 0 at 0.5 m in front, box 1 at 0.8 m behind it and 5 cm to the right: they overlap in the image.
  const std::vector<Pose> poses = {Pose({0, 0, 0.5}, Eigen::Quaterniond::Identity()),
                                   Pose({0.05, 0, 0.8}, Eigen::Quaterniond::Identity())};
  const DepthImage depth = DepthImage::from_metres(80, 60, std::vector<float>(80 * 60, 1.0f));  // working frame
  const MutualOcclusion occlusion(boxes, working, 0.05, 3.0);
  // Box 0's surface (0.45 m) is nearer than box 1 can be anywhere (0.75 m where drawn, its centre 0.8 m less
  // its radius 0.087 m elsewhere): every pixel of box 0's silhouette is hidden from box 1.
  std::vector<float> front(static_cast<size_t>(working.pixel_count()), 0.0f);
  reference::Rasterizer(boxes[0], working, 0.05, 3.0).render(poses[0], front);
  size_t silhouette = 0;
  for (float z : front) silhouette += z > 0;
  REQUIRE(silhouette > 100);
  size_t masked = 0;
  const DepthImage for_back = occlusion.frame_for(1, depth, poses, &masked);
  CHECK(masked == silhouette);
  for (int v = 0; v < working.height; ++v)
    for (int u = 0; u < working.width; ++u) {
      const bool hidden = front[static_cast<size_t>(v) * working.width + u] > 0;
      CHECK(std::isnan(for_back.at(u, v)) == hidden);
      if (!hidden) CHECK(for_back.at(u, v) == 1.0f);  // the others are left alone
    }
  // Box 1 is behind box 0 everywhere: nothing is hidden from box 0.
  occlusion.frame_for(0, depth, poses, &masked);
  CHECK(masked == 0);
  // draw() gives each object's own depth, drawn once (here box 0's equals the rasterizer's above), and the
  // frames made from those layers are the ones drawn per object.
  const std::vector<std::vector<float>> layers = occlusion.draw(poses);
  REQUIRE(layers.size() == 2);
  CHECK(layers[0] == front);
  size_t from_layers = 0;
  const DepthImage same = occlusion.frame_for(1, depth, poses, layers, &from_layers);
  CHECK(from_layers == silhouette);
  for (int v = 0; v < working.height; ++v)
    for (int u = 0; u < working.width; ++u) CHECK(std::isnan(same.at(u, v)) == std::isnan(for_back.at(u, v)));
  CHECK_THROWS_WITH(occlusion.draw({poses[0]}), Contains("1 poses for 2 objects"));
  // The masks are drawn at the working camera: a frame of another size is refused, naming both.
  const DepthImage sensor_sized = DepthImage::from_metres(160, 120, std::vector<float>(160 * 120, 1.0f));
  CHECK_THROWS_WITH(occlusion.frame_for(0, sensor_sized, poses), Contains("160x120, not the working camera's 80x60"));
}

TEST_CASE("MultiTracker refuses no mesh, a null device, a bad index and an object without a start", "[multi][errors]") {
  const Camera camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
  const auto device = Device::open("reference");
  CHECK_THROWS_WITH(MultiTracker(device, {}, camera, TrackerConfig{}), Contains("no mesh"));
  CHECK_THROWS_WITH(MultiTracker(nullptr, {builtin_demo_mesh()}, camera, TrackerConfig{}), Contains("null"));
  TrackerConfig config;
  config.particles = 10;
  MultiTracker two(device, {builtin_demo_mesh(), builtin_demo_mesh()}, camera, config);
  CHECK(two.size() == 2);
  CHECK_THROWS_WITH(two.initialize(2, Pose({0, 0, 0.8}, Eigen::Quaterniond::Identity())),
                    Contains("object 2 does not exist: there are 2"));
  two.initialize(0, Pose({0, 0, 0.8}, Eigen::Quaterniond::Identity()));
  const DepthImage depth = DepthImage::from_metres(80, 60, std::vector<float>(80 * 60, 0.9f));
  CHECK_THROWS_WITH(two.update(depth, 0.0), Contains("object 1 was not initialized"));
}
