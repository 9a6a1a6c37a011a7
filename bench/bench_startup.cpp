// Where a short run's start-up goes (the off-screen start: `track --init "1e7 0 0.06 1 0 0 0"
// --particles 1`): opening the device, each kernel program's build or binary load, the rest of the
// Tracker's construction (buffers, mesh upload), the start and each frame; wall and process CPU
// milliseconds (the CPU of every thread: PoCL's workers too). Run it twice, and once with
// DEPTHTRACK_PROGRAM_CACHE=off, to see the cold, the cached and the uncached start. --trackers N
// constructs N trackers on the one Device (each construction timed): with --renderer gl the later ones
// reuse the Device's GL context, so their construction shows what a tracker's own GL start-up costs.
// Usage: depthtrack_bench_startup [--backend NAME] [--renderer kernel|gl|cpu] [--trackers N] [--frames N]
//                                 [--particles N]
#include <time.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <depthtrack/device.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/synth.hpp>
#include <depthtrack/tracker.hpp>
#include <memory>
#include <string>
#include <vector>

#include "atlas/gl_atlas_device.hpp"
#include "bench_args.hpp"
#include "bench_rows.hpp"
#include "compute/program_cache.hpp"
#include "core/stopwatch.hpp"
#include "tracker/device_access.hpp"

using namespace depthtrack;

namespace {
const char* const kUsage =
    "usage: depthtrack_bench_startup [--backend NAME] [--renderer kernel|gl|cpu] [--trackers N] [--frames N]\n"
    "                                [--particles N]\n"
    "Times the start-up of the off-screen start (a pose 10,000 km to the side): device open, each program's\n"
    "build or load from the binary cache, the rest of the construction, the start and each frame, wall and CPU\n"
    "on the default 640x480 sensor (defaults opencl:pocl, 3 frames, 1 particle; DEPTHTRACK_PROGRAM_CACHE=off\n"
    "for no binary cache). --trackers N constructs N trackers on the one Device, each timed (default 1; with\n"
    "--renderer gl the later ones share the Device's GL context).\n";

double cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

// Wall and CPU time of one phase.
class Phase {
 public:
  void print(const bench::Row& identity, const std::string& phase) const {
    bench::Row row = identity;
    row.test += "_" + phase;
    row.metric = "wall_ms";
    row.unit = "ms";
    row.value = wall_.elapsed_ms();
    bench::print_row(row);
    row.metric = "cpu_ms";
    row.value = cpu_ms() - cpu_start_;
    bench::print_row(row);
  }

 private:
  Stopwatch wall_;
  double cpu_start_ = cpu_ms();
};
}  // namespace

int main(int argc, char** argv) {
  std::string backend = "opencl:pocl";
  int frames = 3, particles = 1, trackers = 1;
  Renderer renderer = Renderer::Kernel;
  const auto option = [&](const std::string& arg, bench::ArgReader& args) {
    if (arg == "--backend")
      backend = args.value();
    else if (arg == "--frames")
      frames = bench::parse_positive(args.value(), arg);
    else if (arg == "--particles")
      particles = bench::parse_positive(args.value(), arg);
    else if (arg == "--trackers")
      trackers = bench::parse_positive(args.value(), arg);
    else if (arg == "--renderer") {
      try {
        renderer = renderer_from_string(args.value());
      } catch (const InputError& e) {
        throw bench::UsageError{std::string("--renderer: ") + e.what()};
      }
    } else
      throw bench::UsageError{"unknown option '" + arg + "'"};
  };
  if (const int status = bench::parse_command_line(argc, argv, "depthtrack_bench_startup", kUsage, option); status >= 0)
    return status;
  try {
    std::string mesh_name;
    const Mesh mesh = bench::bench_mesh(mesh_name);
    SynthConfig synth;
    synth.frames = frames;
    const Synthesizer scene(mesh, synth);
    std::vector<SynthFrame> input;  // drawn first: the synthesis is not the tracker's time
    for (int i = 0; i < frames; ++i) input.push_back(scene.frame(i));
    TrackerConfig config;
    config.backend = backend;
    config.particles = particles;
    config.renderer = renderer;

    bench::print_header();
    const Phase whole;
    const std::string drawn_by = renderer == Renderer::Kernel ? "" : std::string("_") + to_string(renderer);
    bench::Row row{
        backend, backend, "", "-", mesh_name + "_offscreen_startup_" + std::to_string(particles) + "p" + drawn_by,
        "",      "",      0};
    const Phase open;
    const auto device = Device::open(backend);
    row.device = device->name();
    open.print(row, "device_open");
    const Phase construct;
    Tracker tracker(device, mesh, synth.camera, config);
    construct.print(row, "construct");
    // More trackers on the same Device: its programs (and GL context) are there already.
    std::vector<std::unique_ptr<Tracker>> more;
    for (int t = 2; t <= trackers; ++t) {
      const Phase another;
      more.push_back(std::make_unique<Tracker>(device, mesh, synth.camera, config));
      another.print(row, "construct_tracker" + std::to_string(t));
    }
    double programs_ms = 0;
    // A GL tracker's programs are in the context its Device opened against GL, where it shares GL.
    const auto built_on = renderer == Renderer::Gl && DeviceAccess::context(*device)
                              ? DeviceAccess::gl_atlas(*device, config.gl_path).compute
                              : DeviceAccess::context(*device);
    if (built_on)
      for (const auto& r : built_on->programs.records()) {
        programs_ms += r.ms;
        bench::Row program = row;
        program.test += "_program_" + r.file + (r.loaded_from_disk ? "_loaded" : "_built");
        program.metric = "wall_ms";
        program.unit = "ms";
        program.value = r.ms;
        bench::print_row(program);
      }
    bench::Row programs = row;
    programs.test += "_programs_total";
    programs.metric = "wall_ms";
    programs.unit = "ms";
    programs.value = programs_ms;
    bench::print_row(programs);
    const Phase start;
    tracker.initialize(Pose(Eigen::Vector3d(1e7, 0, 0.06), Eigen::Quaterniond::Identity()));
    start.print(row, "initialize");
    for (int i = 0; i < frames; ++i) {
      const Phase frame;
      (void)tracker.update(input[size_t(i)].depth, input[size_t(i)].timestamp);
      frame.print(row, "frame" + std::to_string(i));
    }
    whole.print(row, "total");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "depthtrack_bench_startup: %s\n", e.what());
    return 1;
  }
  return 0;
}
