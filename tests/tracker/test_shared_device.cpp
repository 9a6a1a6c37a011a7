// depthtrack::Device: opening by selector, and several trackers sharing one compute device (one queue,
// each program compiled once) with the estimates they would give on devices of their own.
#include <catch2/catch.hpp>
#include <depthtrack/device.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/multi_tracker.hpp>
#include <depthtrack/synth.hpp>
#include <depthtrack/tracker.hpp>
#include <vector>

#include "compute/program_cache.hpp"
#include "compute/queue.hpp"
#include "device_support.hpp"
#include "filter/device_filter.hpp"
#include "folded_programs.hpp"
#include "same_estimate.hpp"
#include "synth_frames.hpp"
#include "tracker/device_access.hpp"

using namespace depthtrack;
using Catch::Matchers::Contains;

namespace {
// The built-in object's small occluded scene (4 frames) and 64 particles on the test device.
struct SmallDeviceScene {
  Mesh mesh = builtin_demo_mesh();
  SynthConfig synth = test::small_scene(4);
  std::vector<SynthFrame> frames = test::synthesize(mesh, synth);
  TrackerConfig config = [] {
    TrackerConfig c;
    c.particles = 64;
    c.backend = test::device_selector();
    return c;
  }();
};
}  // namespace

TEST_CASE("Device opens host and compute selectors and names a bad one", "[device]") {
  const auto reference = Device::open("reference");
  CHECK(reference->is_host());
  CHECK(reference->name() == "host");
  CHECK(reference->program_builds() == 0);
  CHECK(Device::open("cpu:2")->is_host());
  CHECK_THROWS_WITH(Device::open("cpu:0"), Contains("cpu:0") && Contains("thread count"));
  CHECK_THROWS_WITH(Device::open("quantum"), Contains("unknown backend 'quantum'") && Contains("reference, cpu"));
  CHECK_THROWS_AS(Device::open("opencl:no-such-platform"), InputError);
  // list() is what `depthtrack info` lists.
  const auto listed = Device::list();
  const auto devices = compute::list_devices();
  REQUIRE(listed.size() == devices.size());
  for (size_t i = 0; i < listed.size(); ++i) {
    CHECK(listed[i].selector == devices[i].selector);
    CHECK(listed[i].name == devices[i].name);
    CHECK(listed[i].backend == devices[i].backend);
  }
  CHECK_THROWS_WITH(Tracker(nullptr, builtin_demo_mesh(), test::small_scene(1).camera, TrackerConfig{}),
                    Contains("device is null"));
}

TEST_CASE("A tracker on a host Device equals one that opens its backend itself", "[device]") {
  const Mesh mesh = builtin_demo_mesh();
  const SynthConfig synth = test::small_scene(3);
  const auto frames = test::synthesize(mesh, synth);
  TrackerConfig config;
  config.particles = 40;
  config.backend = "cpu:2";
  Tracker own(mesh, synth.camera, config);
  config.backend = "";  // the Device decides
  Tracker shared(Device::open("cpu:2"), mesh, synth.camera, config);
  CHECK(shared.config().backend == "cpu:2");
  CHECK(shared.backend_description() == own.backend_description());
  own.initialize(frames[0].ground_truth);
  shared.initialize(frames[0].ground_truth);
  for (const auto& f : frames)
    test::require_same_estimate(shared.update(f.depth, f.timestamp), own.update(f.depth, f.timestamp));
}

TEST_CASE("Two trackers on one Device build each program once and track as on their own devices",
          "[device][device_filter]") {
  if (!test::device_available()) return;
  const Mesh mesh = builtin_demo_mesh();
  const SynthConfig synth = test::small_scene(4);
  const auto frames = test::synthesize(mesh, synth);
  TrackerConfig first, second;
  first.particles = second.particles = 64;
  first.backend = second.backend = test::device_selector();
  second.seed = 7;

  const auto device = Device::open(test::device_selector());
  REQUIRE_FALSE(device->is_host());
  Tracker a(device, mesh, synth.camera, first);
  // weigh (at 80x60 render_weigh: the kernel renderer draws inside it), resample, initialize, rasterize
  // (the atlas's and the search's: one key), refine, score, visible_box (the search's box agreement): seven
  // programs; and propagate and summarize where their work is not folded into render_weigh and the
  // one-launch fit (a small cloud's, one-launch).
  const size_t folded_away =
      test::programs_folded_away(*DeviceAccess::context(*device)->queue, mesh, synth.camera, first);
  const size_t builds = device->program_builds();
  CHECK(builds == 9 - folded_away);
  Tracker b(device, mesh, synth.camera, second);
  CHECK(device->program_builds() == builds);  // nothing compiled again
  // Another occlusion mode changes the filter's programs' definitions (all but rasterize and score) and
  // refine's.
  TrackerConfig third = first;
  third.occlusion_storage =
      first.occlusion_storage == OcclusionStorage::Off ? OcclusionStorage::PerPixelTime : OcclusionStorage::Off;
  Tracker c(device, mesh, synth.camera, third);
  CHECK(device->program_builds() == builds + 6 - folded_away);

  Tracker own_a(mesh, synth.camera, first), own_b(mesh, synth.camera, second);
  for (Tracker* t : {&a, &b, &own_a, &own_b}) t->initialize(frames[0].ground_truth);
  for (const auto& f : frames) {
    const Estimate ea = a.update(f.depth, f.timestamp), eb = b.update(f.depth, f.timestamp);
    test::require_same_estimate(ea, own_a.update(f.depth, f.timestamp));
    test::require_same_estimate(eb, own_b.update(f.depth, f.timestamp));
  }
}

// Step timings are diagnostics: without them a frame computes the same, its steps read 0, and the
// host's times and the total stay.
TEST_CASE("A device tracker without step timings tracks the same and times only the whole frame",
          "[device][device_filter]") {
  if (!test::device_available()) return;
  const SmallDeviceScene scene;
  TrackerConfig config = scene.config;
  config.step_timings = true;
  Tracker timed(scene.mesh, scene.synth.camera, config);
  config.step_timings = false;
  Tracker untimed(scene.mesh, scene.synth.camera, config);
  timed.initialize(scene.frames[0].ground_truth);
  untimed.initialize(scene.frames[0].ground_truth);
  // Drawn inside weigh, the particles are moved there too (no propagate launch): its time is weigh's.
  const bool weigh_propagates = propagates_inside_weigh(
      config.renderer, static_cast<size_t>(scene.synth.camera.pixel_count()),
      compute::open_device(test::device_selector())->info().local_memory, static_cast<size_t>(config.particles));
  for (size_t i = 0; i < scene.frames.size(); ++i) {
    const SynthFrame& f = scene.frames[i];
    const Estimate a = timed.update(f.depth, f.timestamp), b = untimed.update(f.depth, f.timestamp);
    test::require_same_estimate(a, b);
    CHECK(a.timings.weigh_ms > 0);
    CHECK(a.timings.resample_ms > 0);
    CHECK(a.timings.refine_ms > 0);
    if (i > 0) CHECK((a.timings.propagate_ms > 0) == !weigh_propagates);
    for (const double step :
         {b.timings.propagate_ms, b.timings.render_ms, b.timings.weigh_ms, b.timings.resample_ms, b.timings.refine_ms})
      CHECK(step == 0);
    CHECK(b.timings.enqueue_ms > 0);
    CHECK(b.timings.wait_ms > 0);
    CHECK(b.timings.total_ms >= b.timings.enqueue_ms + b.timings.wait_ms);
  }
}

TEST_CASE("A Device's queues share memory and programs: what one writes another reads", "[device]") {
  if (!test::device_available()) return;
  const auto device = Device::open(test::device_selector());
  compute::Queue& first = *DeviceAccess::context(*device)->queue;
  const std::unique_ptr<compute::Queue> second = DeviceAccess::context(*device)->make_queue();
  REQUIRE(second);  // OpenCL (PoCL) and CUDA both offer queues of their own
  CHECK(second->info().name == first.info().name);
  const std::vector<float> values = {1.5f, -2.0f, 3.25f};
  const auto memory = first.allocate(values.size() * sizeof(float));
  first.write(*memory, 0, values.data(), values.size() * sizeof(float));
  std::vector<float> back(values.size());
  second->read(*memory, 0, back.data(), back.size() * sizeof(float));
  CHECK(back == values);
}

TEST_CASE("A MultiTracker's objects, enqueued together on one Device, equal single trackers run one by one",
          "[device][device_filter][multi]") {
  if (!test::device_available()) return;
  const SmallDeviceScene scene;
  const Mesh& mesh = scene.mesh;
  const SynthConfig& synth = scene.synth;
  const auto& frames = scene.frames;
  TrackerConfig config = scene.config;
  // Three objects: the synthetic object's own pose and 4 cm to either side (those two track clutter).
  std::vector<Pose> starts(3, frames[0].ground_truth);
  starts[1].translation.x() -= 0.04;
  starts[2].translation.x() += 0.04;
  MultiTracker together(Device::open(test::device_selector()), {mesh, mesh, mesh}, synth.camera, config,
                        /*mutual_occlusion=*/false);
  std::vector<Tracker> alone;
  for (size_t j = 0; j < 3; ++j) {
    together.initialize(j, starts[j]);
    alone.emplace_back(mesh, synth.camera, config);
    alone.back().initialize(starts[j]);
  }
  for (const auto& f : frames) {
    const std::vector<Estimate> estimates = together.update(f.depth, f.timestamp);
    REQUIRE(estimates.size() == 3);
    for (size_t j = 0; j < 3; ++j) test::require_same_estimate(estimates[j], alone[j].update(f.depth, f.timestamp));
  }
}
