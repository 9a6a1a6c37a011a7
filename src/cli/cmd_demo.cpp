// depthtrack demo: synthesize an occluded sequence of the built-in object, track it, print the errors.
#include <chrono>
#include <cstdio>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/synth.hpp>
#include <memory>
#include <numbers>

#include "cli/commands.hpp"
#include "cli/tracker_options.hpp"

namespace depthtrack::cli {

namespace {

struct DemoArgs {
  int frames = 90;
  double occluder = 0.3;
  TrackerOptions tracker;
};

void run_demo(const DemoArgs& a) {
  const TrackerConfig config = a.tracker.resolve();
  const Mesh mesh = builtin_demo_mesh();
  SynthConfig synth;
  synth.frames = a.frames;
  synth.occluder_fraction = a.occluder;
  synth.seed = config.seed;
  const Synthesizer synthesizer(mesh, synth);

  Tracker tracker(mesh, synth.camera, config);
  tracker.initialize(synthesizer.ground_truth(0.0));
  std::printf("depthtrack demo: built-in object (%zu triangles), %d frames at %.0f Hz, %.0f %% occluder,\n",
              mesh.triangles.size(), synth.frames, synth.rate, 100 * synth.occluder_fraction);
  std::printf("structured-light sensor %dx%d, tracked at %dx%d with %d particles, backend %s, occlusion %s\n\n",
              synth.camera.width, synth.camera.height, config.width, config.height, config.particles,
              tracker.backend_description().c_str(), to_string(config.occlusion_storage));
  std::printf("%6s %9s %10s %10s %8s %9s\n", "frame", "time s", "err mm", "err deg", "ESS", "ms");
  const double deg = 180.0 / std::numbers::pi;
  double sum_t = 0, sum_r = 0, max_t = 0, tracking_seconds = 0;
  for (int i = 0; i < synth.frames; ++i) {
    const SynthFrame f = synthesizer.frame(i);
    const auto start = std::chrono::steady_clock::now();
    const Estimate e = tracker.update(f.depth, f.timestamp);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    tracking_seconds += seconds;
    const double et = translation_error(e.pose, f.ground_truth), er = rotation_error(e.pose, f.ground_truth);
    sum_t += et;
    sum_r += er;
    max_t = std::max(max_t, et);
    std::printf("%6d %9.3f %10.2f %10.2f %8.1f %9.2f\n", i, f.timestamp, 1000 * et, deg * er, e.effective_sample_size,
                1000 * seconds);
  }
  const double n = synth.frames;
  std::printf("\nmean error %.2f mm / %.2f deg, max %.2f mm; %.1f frames per second (tracking only)\n",
              1000 * sum_t / n, deg * sum_r / n, 1000 * max_t, n / tracking_seconds);
}

}  // namespace

void add_demo_command(CLI::App& app) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* c = app.add_subcommand(
      "demo",
      "Synthesize an occluded depth sequence of a built-in object, track it and print per-frame errors and fps");
  c->add_option("--frames", args->frames, "Number of frames (30 Hz)")->capture_default_str();
  c->add_option("--occluder", args->occluder, "Share of the object hidden by a moving occluder, 0..0.9")
      ->capture_default_str();
  args->tracker.add_to(*c);
  c->callback([args] { run_demo(*args); });
}

}  // namespace depthtrack::cli
