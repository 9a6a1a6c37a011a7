// Mutual occlusion: which pixels one object's estimate hides from another (hand-placed boxes), the
// MultiTracker's masks (made from its trackers' confidence renderings) against masks drawn afresh, and the
// MultiTracker's refusals.
#include <catch2/catch.hpp>
#include <cmath>
#include <depthtrack/error.hpp>
#include <depthtrack/multi_tracker.hpp>
#include <depthtrack/synth.hpp>

#include "reference/rasterizer.hpp"
#include "synth_frames.hpp"
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
  const MutualOcclusion occlusion(boxes, working);
  // Box 0's surface (0.45 m) is nearer than box 1 can be anywhere (0.75 m where drawn, its centre 0.8 m less
  // its radius 0.087 m elsewhere): every pixel of box 0's silhouette is hidden from box 1.
  std::vector<std::vector<float>> layers(2, std::vector<float>(static_cast<size_t>(working.pixel_count()), 0.0f));
  for (size_t k = 0; k < 2; ++k) reference::Rasterizer(boxes[k], working, 0.05, 3.0).render(poses[k], layers[k]);
  const std::vector<float>& front = layers[0];
  size_t silhouette = 0;
  for (float z : front) silhouette += z > 0;
  REQUIRE(silhouette > 100);
  size_t masked = 0;
  const DepthImage for_back = occlusion.frame_for(1, depth, poses, layers, &masked);
  CHECK(masked == silhouette);
  for (int v = 0; v < working.height; ++v)
    for (int u = 0; u < working.width; ++u) {
      const bool hidden = front[static_cast<size_t>(v) * working.width + u] > 0;
      CHECK(std::isnan(for_back.at(u, v)) == hidden);
      if (!hidden) CHECK(for_back.at(u, v) == 1.0f);  // the others are left alone
    }
  // Box 1 is behind box 0 everywhere: nothing is hidden from box 0.
  occlusion.frame_for(0, depth, poses, layers, &masked);
  CHECK(masked == 0);
  CHECK_THROWS_WITH(occlusion.frame_for(0, depth, {poses[0]}, layers), Contains("1 poses and 2 layers for 2 objects"));
  CHECK_THROWS_WITH(occlusion.frame_for(0, depth, poses, {layers[0], std::vector<float>(7)}),
                    Contains("a layer of 7 pixels, not the working camera's 4800"));
  // The masks are drawn at the working camera: a frame of another size is refused, naming both.
  const DepthImage sensor_sized = DepthImage::from_metres(160, 120, std::vector<float>(160 * 120, 1.0f));
  CHECK_THROWS_WITH(occlusion.frame_for(0, sensor_sized, poses, layers),
                    Contains("160x120, not the working camera's 80x60"));
}

TEST_CASE("MultiTracker refuses no mesh, a null device, a bad thread count, a bad index and an object without a start",
          "[multi][errors]") {
  const Camera camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);
  const auto device = Device::open("reference");
  CHECK_THROWS_WITH(MultiTracker(device, {}, camera, TrackerConfig{}), Contains("no mesh"));
  CHECK_THROWS_WITH(MultiTracker(nullptr, {builtin_demo_mesh()}, camera, TrackerConfig{}), Contains("null"));
  CHECK_THROWS_WITH(MultiTracker(device, {builtin_demo_mesh()}, camera, TrackerConfig{}, true, -1),
                    Contains("host_threads is -1: give 0 (one per object) or a count from 1 to 1024"));
  CHECK_THROWS_WITH(MultiTracker(device, {builtin_demo_mesh()}, camera, TrackerConfig{}, true, 5000),
                    Contains("host_threads is 5000"));
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

TEST_CASE("MultiTracker's masks, from the confidence's renderings, equal masks drawn afresh each frame", "[multi]") {
  // Three copies of the synthetic object side by side, 3 cm apart, so that each one's silhouette
  // overlaps the next; frame 2 a dropout (no confidence drawn: the next masks need fresh drawings).
  const Mesh mesh = builtin_demo_mesh();
  SynthConfig synth;
  synth.camera = synth.camera.decimated(8);  // 80x60, the working resolution
  synth.frames = 5;
  auto frames = test::synthesize(mesh, synth);
  frames[2].depth = DepthImage::from_metres(80, 60, std::vector<float>(80 * 60, std::nanf("")));
  TrackerConfig config;
  config.particles = 32;
  std::vector<Pose> starts(3, frames[0].ground_truth);
  starts[1].translation.x() -= 0.03;
  starts[2].translation.x() += 0.03;
  MultiTracker together(Device::open("reference"), {mesh, mesh, mesh}, synth.camera, config);
  // The same on the calling thread alone: the pool changes no number.
  MultiTracker serial(Device::open("reference"), {mesh, mesh, mesh}, synth.camera, config, true, 1);
  // The expectation: trackers of their own, each fed its frame masked by MutualOcclusion from layers
  // the reference rasterizer draws at the previous estimates.
  std::vector<Tracker> alone;
  for (size_t j = 0; j < 3; ++j) {
    together.initialize(j, starts[j]);
    serial.initialize(j, starts[j]);
    alone.emplace_back(mesh, synth.camera, config);
    alone.back().initialize(starts[j]);
  }
  const MutualOcclusion occlusion({mesh, mesh, mesh}, synth.camera);
  const reference::Rasterizer rasterizer(mesh, synth.camera, config.near_plane, config.observation.max_depth);
  std::vector<Pose> previous = starts;
  size_t masked_pixels = 0;
  for (const auto& f : frames) {
    std::vector<std::vector<float>> layers(3, std::vector<float>(80 * 60));
    for (size_t k = 0; k < 3; ++k) rasterizer.render(previous[k], layers[k]);
    const std::vector<Estimate> estimates = together.update(f.depth, f.timestamp);
    const std::vector<Estimate> one_thread = serial.update(f.depth, f.timestamp);
    REQUIRE(estimates.size() == 3);
    for (size_t j = 0; j < 3; ++j) {
      REQUIRE(one_thread[j].pose.translation == estimates[j].pose.translation);
      REQUIRE(one_thread[j].pose.rotation.coeffs() == estimates[j].pose.rotation.coeffs());
      REQUIRE(one_thread[j].confidence == estimates[j].confidence);
      size_t masked = 0;
      const Estimate own = alone[j].update(occlusion.frame_for(j, f.depth, previous, layers, &masked), f.timestamp);
      masked_pixels += masked;
      REQUIRE(estimates[j].pose.translation == own.pose.translation);
      REQUIRE(estimates[j].pose.rotation.coeffs() == own.pose.rotation.coeffs());
      REQUIRE(estimates[j].confidence == own.confidence);
      REQUIRE(estimates[j].status == own.status);
    }
    for (size_t j = 0; j < 3; ++j) previous[j] = estimates[j].pose;
  }
  CHECK(masked_pixels > 100);  // the objects did hide each other
}
