// The device filter draws its initial particles and fills its occlusion state on the device
// (cl/initialize.cl): the same seed gives the reference's particles to float precision, and the
// state after initialize() is the reference's, however many frames ran before.
#include <catch2/catch.hpp>
#include <depthtrack/synth.hpp>

#include "device_support.hpp"
#include "filter/device_filter.hpp"
#include "filter/device_filter_probe.hpp"
#include "reference/reference_filter.hpp"

using namespace depthtrack;

namespace {
void require_same_start(const reference::ReferenceFilter& reference, DeviceFilter& device) {
  const auto expected = reference.particles();
  const auto drawn = DeviceFilterProbe(device).particles();
  REQUIRE(drawn.size() == expected.size());
  double worst_t = 0, worst_r = 0;
  for (size_t i = 0; i < drawn.size(); ++i) {
    worst_t = std::max(worst_t, translation_error(drawn[i].pose, expected[i].pose));
    worst_r = std::max(worst_r, rotation_error(drawn[i].pose, expected[i].pose));
    REQUIRE(drawn[i].linear_velocity.isZero());
    REQUIRE(drawn[i].angular_velocity.isZero());
  }
  // The tolerances of the frame-by-frame equivalence test (float poses against double ones).
  CHECK(worst_t <= 1e-5);
  CHECK(worst_r <= 1e-4);
  CHECK(DeviceFilterProbe(device).occlusion_state() == reference.occlusion_state());
  CHECK(DeviceFilterProbe(device).occlusion_times() == reference.occlusion_times());
}
}  // namespace

TEST_CASE("initial particles and occlusion state drawn on the device equal the reference's", "[device][init]") {
  if (!test::device_available()) return;
  const Mesh mesh = builtin_demo_mesh();
  const SynthConfig synth;
  const Synthesizer synthesizer(mesh, synth);
  const Camera camera = synth.camera.decimated(8);
  for (auto mode : {OcclusionStorage::PerPixelTime, OcclusionStorage::GlobalTime, OcclusionStorage::Off}) {
    INFO("occlusion mode " << static_cast<int>(mode));
    TrackerConfig config;
    config.particles = 300;  // not a multiple of any work-group size
    config.occlusion_storage = mode;
    config.seed = 0x1234'5678'9abcULL;  // both halves of the 64-bit seed matter
    config.backend = test::device_selector();
    reference::ReferenceFilter reference(mesh, camera, config);
    DeviceFilter device(compute::open_device(config.backend), mesh, camera, config);
    const SynthFrame first = synthesizer.frame(0);
    const Pose turned(first.ground_truth.translation,
                      first.ground_truth.rotation *
                          Eigen::Quaterniond(Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 2, 3).normalized())));
    const InitialSpread spread{0.02, 0.1};
    reference.initialize(turned, spread);
    device.initialize(turned, spread);
    require_same_start(reference, device);
    // The spread is really drawn: the particles are not all the start pose.
    const auto drawn = DeviceFilterProbe(device).particles();
    CHECK(translation_error(drawn[0].pose, drawn[1].pose) > 1e-3);

    // A second initialize() after frames have changed every buffer starts afresh.
    for (int f = 0; f < 3; ++f) {
      const SynthFrame frame = synthesizer.frame(f);
      const DepthImage depth = frame.depth.decimated(8);
      reference.update(depth, f == 0 ? 0.0 : 1.0 / 30);
      device.update(depth, f == 0 ? 0.0 : 1.0 / 30);
    }
    reference.initialize(first.ground_truth, spread);
    device.initialize(first.ground_truth, spread);
    require_same_start(reference, device);
    // Log-weights are zero again: the first frame's weights are its likelihoods alone.
    const DepthImage depth = first.depth.decimated(8);
    const Estimate a = reference.update(depth, 0.0), b = device.update(depth, 0.0);
    CHECK(b.effective_sample_size == Approx(a.effective_sample_size).epsilon(1e-3).margin(1e-3));
  }
}
