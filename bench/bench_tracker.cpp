// Time per frame of the tracker on one backend, split into propagate, render, hand-off, weigh, resample
// and refine (the pose refinement with the shift of the cloud; refine_share is its % of the frame),
// with the handset (the thesis' object) on a synthetic occluded sequence. Prints CSV rows.
// render is the atlas draw (GL waited for); handoff moves poses to GL and the atlas to the kernels.
// Usage: depthtrack_bench [--backend NAME] [--renderer kernel|gl|cpu] [--particles N[,N...]] [--resolution WxH[,...]]
//                         [--frames N] [--refine on|off] [--refine-iterations N]
//   default: the reference at 80x60 (200 particles) and 640x480 (50 particles).
// Then global initialization at 80x60 (from the object's box, and from no hint), unless --no-global.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <depthtrack/error.hpp>
#include <depthtrack/init_hint.hpp>
#include <depthtrack/synth.hpp>
#include <depthtrack/tracker.hpp>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "bench_rows.hpp"
#include "core/stopwatch.hpp"
#include "host_memory.hpp"

using namespace depthtrack;

namespace {

struct Case {
  int width, height, particles;
};

void run(const Mesh& mesh, const std::string& mesh_name, const std::string& backend, const std::string& renderer,
         const Refinement& refine, const Case& c, int frames) {
  SynthConfig synth;
  synth.frames = frames;
  synth.occluder_fraction = 0.3;
  const Synthesizer scene(mesh, synth);
  TrackerConfig config;
  config.backend = backend;
  config.renderer = renderer_from_string(renderer);
  config.width = c.width;
  config.height = c.height;
  config.particles = c.particles;
  config.refine = refine;
  // Start-up: construction (device buffers, kernels built or read from the driver's cache) and the
  // initial particle and occlusion state, with the host memory it peaks at.
  const bool peak_known = bench::reset_peak_resident();
  const Stopwatch startup;
  Tracker tracker(mesh, synth.camera, config);
  tracker.initialize(scene.ground_truth(0.0));
  const double startup_ms = startup.elapsed_ms();
  const double startup_peak_mib = peak_known ? bench::peak_resident_mib() : NAN;
  std::vector<double> propagate, render, handoff, weigh, resample, refined, total;
  for (int i = 0; i < frames; ++i) {
    const SynthFrame f = scene.frame(i);
    const Estimate e = tracker.update(f.depth, f.timestamp);
    if (i < 2) continue;  // warm-up: caches, first-frame propagation skipped
    propagate.push_back(e.timings.propagate_ms);
    render.push_back(e.timings.render_ms);
    handoff.push_back(e.timings.handoff_ms);
    weigh.push_back(e.timings.weigh_ms);
    resample.push_back(e.timings.resample_ms);
    refined.push_back(e.timings.refine_ms);
    total.push_back(e.timings.total_ms);
  }
  const std::string device = tracker.backend_description();
  const std::string test = (backend == "reference" ? "" : renderer + "_") + mesh_name + "_" + std::to_string(c.width) +
                           "x" + std::to_string(c.height) + "_" + std::to_string(c.particles) + "p" +
                           (refine.enabled ? "_refine" + std::to_string(refine.iterations) : "_norefine");
  const std::string platform = backend == "reference" ? "cpu" : backend;
  const std::string name = backend == "reference" ? bench::cpu_name() : device;
  for (const auto& [metric, samples] : {std::pair{"propagate", &propagate},
                                        {"render", &render},
                                        {"handoff", &handoff},
                                        {"weigh", &weigh},
                                        {"resample", &resample},
                                        {"refine", &refined},
                                        {"total", &total}}) {
    const double ms = bench::median(*samples);
    bench::print_row({backend, platform, name, "-", test, std::string(metric) + "_ms", "ms", ms});
    bench::print_row(
        {backend, platform, name, "-", test, std::string(metric) + "_per_particle", "us", 1000.0 * ms / c.particles});
  }
  bench::print_row(
      {backend, platform, name, "-", test, "refine_share", "%", 100.0 * bench::median(refined) / bench::median(total)});
  bench::print_row({backend, platform, name, "-", test, "frames_per_second", "Hz", 1000.0 / bench::median(total)});
  bench::print_row({backend, platform, name, "-", test, "startup_ms", "ms", startup_ms});
  bench::print_row({backend, platform, name, "-", test, "startup_host_peak", "MiB", startup_peak_mib});
}

const char* const kUsage =
    "usage: depthtrack_bench [--backend NAME] [--renderer kernel|gl|cpu] [--particles N[,N...]] "
    "[--resolution WxH[,...]] [--frames N] [--refine on|off] [--refine-iterations N] [--no-global]\n"
    "Times tracker frames on a synthetic occluded handset sequence, split into propagate / render / hand-off /\n"
    "weigh / resample, and start-up (construction + initialize) with its peak host memory; prints CSV rows\n"
    "backend,platform,device,driver,test,metric,unit,value.\n"
    "  --backend NAME         reference (default), opencl, opencl:pocl, cuda, ... (`depthtrack info`)\n"
    "  --renderer NAME        atlas renderer of device backends: kernel (default), gl, cpu\n"
    "  --particles N[,N...]   particle counts (default 200)\n"
    "  --resolution WxH[,...] working resolutions (default 80x60)\n"
    "  --frames N             frames per case, the first two not timed (default 20, at least 4)\n"
    "  --refine on|off        the pose refinement (default on; refine_share is its % of the frame)\n"
    "  --refine-iterations N  refinement steps per frame (default: TrackerConfig's)\n"
    "  --no-global            leave out the global initialization rows (box hint and no hint, 80x60)\n"
    "Without --particles and --resolution: the reference at 80x60 (200 particles) and 640x480 (50).\n";

// The sensor-pixel box around the object's projected vertices: what a detector would give.
InitHint object_box(const Mesh& mesh, const Camera& camera, const Pose& pose) {
  double u0 = camera.width, v0 = camera.height, u1 = 0, v1 = 0;
  for (const auto& v : mesh.vertices) {
    const Eigen::Vector2d p = camera.project(pose.apply(v.cast<double>()));
    u0 = std::min(u0, p.x());
    v0 = std::min(v0, p.y());
    u1 = std::max(u1, p.x());
    v1 = std::max(v1, p.y());
  }
  auto clamp = [](double x, int size) { return std::clamp(static_cast<int>(std::lround(x)), 0, size - 1); };
  return InitHint::box(clamp(u0, camera.width), clamp(v0, camera.height), clamp(u1, camera.width),
                       clamp(v1, camera.height));
}

// Global initialization (Tracker::initialize_global) at 80x60 on the first synthetic frame, from
// the object's box and from no hint: search time, poses scored, and the error it starts from.
void run_global(const Mesh& mesh, const std::string& mesh_name, const std::string& backend, int particles) {
  SynthConfig synth;
  synth.frames = 1;
  synth.occluder_fraction = 0.3;
  const SynthFrame f = Synthesizer(mesh, synth).frame(0);
  TrackerConfig config;
  config.backend = backend;
  config.particles = particles;
  for (const auto& [start, hint] :
       {std::pair{"box", object_box(mesh, synth.camera, f.ground_truth)}, std::pair{"none", InitHint::anywhere()}}) {
    Tracker tracker(mesh, synth.camera, config);
    const Estimate e = tracker.initialize_global(f.depth, f.timestamp, hint);
    const std::string test = std::string("global_init_") + start + "_" + mesh_name + "_80x60";
    const std::string platform = backend == "reference" ? "cpu" : backend;
    const std::string name = backend == "reference" ? bench::cpu_name() : tracker.backend_description();
    bench::print_row({backend, platform, name, "-", test, "search_ms", "ms", e.timings.search_ms});
    bench::print_row(
        {backend, platform, name, "-", test, "poses_scored", "poses", static_cast<double>(e.search_poses)});
    bench::print_row({backend, platform, name, "-", test, "poses_per_second", "1/s",
                      1000.0 * static_cast<double>(e.search_poses) / e.timings.search_ms});
    bench::print_row({backend, platform, name, "-", test, "error_after_first_frame", "mm",
                      1000 * translation_error(e.pose, f.ground_truth)});
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string backend = "reference", renderer = "kernel";
  std::vector<int> particle_counts;
  std::vector<std::pair<int, int>> sizes;
  int frames = 20;
  Refinement refine;
  bool global = true;
  try {
    bench::ArgReader args(argc, argv);
    for (std::string arg = args.next(); !arg.empty(); arg = args.next()) {
      if (arg == "--help" || arg == "-h") {
        std::printf("%s", kUsage);
        return 0;
      }
      if (arg == "--backend")
        backend = args.value();
      else if (arg == "--renderer")
        renderer = args.value();
      else if (arg == "--particles")
        particle_counts = bench::parse_positive_list(args.value(), arg);
      else if (arg == "--resolution")
        for (const std::string& r : bench::split(args.value())) sizes.push_back(bench::parse_size(r, arg));
      else if (arg == "--frames")
        frames = bench::parse_positive(args.value(), arg);
      else if (arg == "--refine") {
        const std::string value = args.value();
        if (value != "on" && value != "off") throw bench::UsageError{"--refine takes on or off, not '" + value + "'"};
        refine.enabled = value == "on";
      } else if (arg == "--refine-iterations")
        refine.iterations = bench::parse_positive(args.value(), arg);
      else if (arg == "--no-global")
        global = false;
      else
        throw bench::UsageError{"unknown option '" + arg + "'"};
    }
  } catch (const bench::UsageError& e) {
    std::fprintf(stderr, "depthtrack_bench: %s\n%s", e.message.c_str(), kUsage);
    return 2;
  }
  std::vector<Case> cases;
  if (particle_counts.empty() && sizes.empty()) {
    cases = {{80, 60, 200}, {640, 480, 50}};
  } else {
    if (sizes.empty()) sizes = {{80, 60}};
    if (particle_counts.empty()) particle_counts = {200};
    for (const auto& [width, height] : sizes)
      for (const int p : particle_counts) cases.push_back({width, height, p});
  }
  try {
    std::string name;
    const Mesh mesh = bench::bench_mesh(name);
    bench::print_header();
    int failed = 0;
    for (const Case& c : cases) {
      // A case the device cannot run (too many particles for its memory) gets a status row, and
      // the others still run.
      try {
        run(mesh, name, backend, renderer, refine, c, std::max(frames, 4));
      } catch (const Error& e) {
        ++failed;
        const std::string test = renderer + "_" + name + "_" + std::to_string(c.width) + "x" +
                                 std::to_string(c.height) + "_" + std::to_string(c.particles) + "p";
        bench::print_status(backend, test, e.what());
      }
    }
    if (global) {
      try {
        run_global(mesh, name, backend, cases.front().particles);
      } catch (const Error& e) {
        ++failed;
        bench::print_status(backend, "global_init_" + name + "_80x60", e.what());
      }
    }
    return failed == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "depthtrack_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
