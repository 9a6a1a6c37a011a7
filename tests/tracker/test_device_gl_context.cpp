// A Device's GL context: made by its first GL tracker, shared by the GL trackers made on the same thread
// (each with its own framebuffers and buffers in it), one per thread, and none for kernel-renderer trackers;
// trackers sharing it track exactly as trackers with contexts of their own.
#include <catch2/catch.hpp>
#include <depthtrack/device.hpp>
#include <depthtrack/multi_tracker.hpp>
#include <depthtrack/synth.hpp>
#include <depthtrack/tracker.hpp>
#include <thread>
#include <vector>

#include "device_support.hpp"
#include "same_estimate.hpp"
#include "synth_frames.hpp"

using namespace depthtrack;

namespace {

TrackerConfig gl_config(unsigned seed) {
  TrackerConfig config;
  config.particles = 40;
  config.backend = test::device_selector();
  config.renderer = Renderer::Gl;
  config.seed = seed;
  return config;
}

}  // namespace

TEST_CASE("GL trackers on one Device share one GL context and track as with contexts of their own",
          "[device][render][device_filter]") {
  if (!test::device_available() || !test::gl_built()) return;
  const Mesh mesh = builtin_demo_mesh();
  const SynthConfig synth = test::small_scene(3);
  const auto frames = test::synthesize(mesh, synth);
  const auto device = Device::open(test::device_selector());
  CHECK(device->gl_contexts() == 0);
  TrackerConfig kernel = gl_config(1);
  kernel.renderer = Renderer::Kernel;
  Tracker drawn_by_kernel(device, mesh, synth.camera, kernel);
  CHECK(device->gl_contexts() == 0);  // the kernel renderer needs no GL

  Tracker a(device, mesh, synth.camera, gl_config(1)), b(device, mesh, synth.camera, gl_config(7));
  CHECK(device->gl_contexts() == 1);
  Tracker own_a(mesh, synth.camera, gl_config(1)), own_b(mesh, synth.camera, gl_config(7));
  // Same GL, same hand-off (and the same reason for it) as on a Device of its own.
  CHECK(a.backend_description() == own_a.backend_description());
  INFO(a.backend_description());
  for (Tracker* t : {&a, &b, &own_a, &own_b}) t->initialize(frames[0].ground_truth);
  for (const auto& f : frames) {  // interleaved: each draw in the shared context follows the other's
    const Estimate ea = a.update(f.depth, f.timestamp), eb = b.update(f.depth, f.timestamp);
    test::require_same_estimate(ea, own_a.update(f.depth, f.timestamp));
    test::require_same_estimate(eb, own_b.update(f.depth, f.timestamp));
  }

  // A MultiTracker's objects, made on this thread, draw in the same context.
  MultiTracker several(device, {mesh, mesh}, synth.camera, gl_config(3));
  CHECK(device->gl_contexts() == 1);
}

TEST_CASE("a GL tracker made on another thread gets that thread's GL context and tracks there",
          "[device][render][device_filter]") {
  if (!test::device_available() || !test::gl_built()) return;
  const Mesh mesh = builtin_demo_mesh();
  const SynthConfig synth = test::small_scene(2);
  const auto frames = test::synthesize(mesh, synth);
  const auto device = Device::open(test::device_selector());
  Tracker here(device, mesh, synth.camera, gl_config(1));
  here.initialize(frames[0].ground_truth);
  (void)here.update(frames[0].depth, frames[0].timestamp);

  // The context above is current on this thread, where EGL keeps it: the other thread needs its own.
  std::vector<Estimate> there;
  std::string error;
  std::thread worker([&] {
    try {
      Tracker tracker(device, mesh, synth.camera, gl_config(5));
      tracker.initialize(frames[0].ground_truth);
      for (const auto& f : frames) there.push_back(tracker.update(f.depth, f.timestamp));
    } catch (const std::exception& e) {
      error = e.what();
    }
  });
  worker.join();
  REQUIRE(error.empty());
  CHECK(device->gl_contexts() == 2);
  Tracker own(mesh, synth.camera, gl_config(5));
  own.initialize(frames[0].ground_truth);
  for (size_t i = 0; i < frames.size(); ++i)
    test::require_same_estimate(there[i], own.update(frames[i].depth, frames[i].timestamp));
  (void)here.update(frames[1].depth, frames[1].timestamp);  // this thread's tracker is undisturbed
}
