// A long run with hostile moments mixed in: memory must stay flat and no estimate may be NaN.
// Every 250th frame is a dropout (no valid pixel), every 100th carries a reading at 300 m on the
// object (beyond max_depth: missing), every 500th follows a 10 s gap. Prints CSV rows every
// --every frames: resident memory (MiB), frames done, non-finite estimates, no-data frames, and
// the translation error (mm) against the synthetic truth.
// Usage: depthtrack_bench_soak [--backend NAME] [--frames 3000] [--every 500] [--particles 200]
#include <cmath>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <depthtrack/synth.hpp>
#include <depthtrack/tracker.hpp>
#include <string>

#include "bench_args.hpp"
#include "bench_rows.hpp"
#include "host_memory.hpp"

using namespace depthtrack;

namespace {
const char* const kUsage =
    "usage: depthtrack_bench_soak [--backend NAME] [--frames N] [--every N] [--particles N]\n"
    "Tracks a long synthetic sequence with dropouts, far readings and 10 s gaps mixed in; prints resident\n"
    "memory, non-finite estimates, no-data frames and the error every --every frames (defaults 3000, 500, 200).\n";
}  // namespace

int main(int argc, char** argv) {
  std::string backend = "reference";
  int frames = 3000, every = 500, particles = 200;
  const auto option = [&](const std::string& arg, bench::ArgReader& args) {
    if (arg == "--backend")
      backend = args.value();
    else if (arg == "--frames")
      frames = bench::parse_positive(args.value(), arg);
    else if (arg == "--every")
      every = bench::parse_positive(args.value(), arg);
    else if (arg == "--particles")
      particles = bench::parse_positive(args.value(), arg);
    else
      throw bench::UsageError{"unknown option '" + arg + "'"};
  };
  if (const int status = bench::parse_command_line(argc, argv, "depthtrack_bench_soak", kUsage, option); status >= 0)
    return status;
  try {
    std::string mesh_name;
    const Mesh mesh = bench::bench_mesh(mesh_name);
    SynthConfig synth;
    synth.camera = Camera::make(80, 60, 65.625, 65.625, 39.9375, 29.9375);  // working resolution: no decimation
    synth.frames = frames;
    synth.occluder_fraction = 0.3;
    const Synthesizer scene(mesh, synth);
    TrackerConfig config;
    config.backend = backend;
    config.particles = particles;
    Tracker tracker(mesh, synth.camera, config);
    tracker.initialize(scene.ground_truth(0.0));
    const std::string test = "soak_" + mesh_name + "_80x60_" + std::to_string(particles) + "p";
    const std::string platform = backend == "reference" ? "cpu" : backend;
    const std::string device = tracker.backend_description();
    bench::print_header();
    int non_finite = 0, no_data = 0;
    double gap = 0, error_sum = 0;
    for (int i = 0; i < frames; ++i) {
      SynthFrame f = scene.frame(i);
      if (i > 0 && i % 500 == 0) gap += 10.0;
      if (i > 0 && i % 250 == 0) f.depth = DepthImage(f.depth.width(), f.depth.height());
      if (i % 100 == 50) f.depth.at(40, 30) = 300.0f;
      const Estimate e = tracker.update(f.depth, f.timestamp + gap);
      const bool finite = e.pose.translation.allFinite() && e.pose.rotation.coeffs().allFinite();
      non_finite += !finite;
      no_data += e.status == TrackStatus::NoData;
      error_sum += (e.pose.translation - f.ground_truth.translation).norm();
      if ((i + 1) % every == 0 || i + 1 == frames) {
        const double done = i + 1;
        for (const auto& [metric, unit, value] : {std::tuple{"frames", "count", done},
                                                  {"resident_memory", "MiB", bench::resident_mib()},
                                                  {"non_finite_estimates", "count", static_cast<double>(non_finite)},
                                                  {"no_data_frames", "count", static_cast<double>(no_data)},
                                                  {"mean_translation_error", "mm", 1000 * error_sum / done}})
          bench::print_row({backend, platform, device, "", test, metric, unit, value});
        std::fflush(stdout);
      }
    }
    return non_finite == 0 ? 0 : 1;
  } catch (const Error& e) {
    bench::print_status(backend, "soak", e.what());
    return 1;
  }
}
