// Time per frame of the tracker on one backend, split into propagate, render, hand-off, weigh, resample
// and refine (the pose refinement with the shift of the cloud; refine_share is its % of the frame),
// with the handset (the thesis' object) on a synthetic occluded sequence. Prints CSV rows.
// render is the atlas draw (GL waited for); handoff moves poses to GL and the atlas to the kernels.
// Usage: depthtrack_bench [--backend NAME] [--renderer kernel|gl|cpu] [--particles N[,N...]] [--resolution WxH[,...]]
//                         [--frames N] [--refine on|off] [--refine-iterations N]
//   default: the reference at 80x60 (200 particles) and 640x480 (50 particles).
#include <cstdio>
#include <cstring>
#include <depthtrack/error.hpp>
#include <depthtrack/synth.hpp>
#include <depthtrack/tracker.hpp>
#include <string>
#include <vector>

#include "bench_rows.hpp"

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
  config.renderer = renderer;
  config.width = c.width;
  config.height = c.height;
  config.particles = c.particles;
  config.refine = refine;
  Tracker tracker(mesh, synth.camera, config);
  tracker.initialize(scene.ground_truth(0.0));
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
}

}  // namespace

int main(int argc, char** argv) {
  std::string backend = "reference", renderer = "kernel", particles, resolutions;
  int frames = 20;
  Refinement refine;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--backend" && i + 1 < argc)
      backend = argv[++i];
    else if (arg == "--renderer" && i + 1 < argc)
      renderer = argv[++i];
    else if (arg == "--particles" && i + 1 < argc)
      particles = argv[++i];
    else if (arg == "--resolution" && i + 1 < argc)
      resolutions = argv[++i];
    else if (arg == "--frames" && i + 1 < argc)
      frames = std::atoi(argv[++i]);
    else if (arg == "--refine" && i + 1 < argc &&
             (std::string(argv[i + 1]) == "on" || std::string(argv[i + 1]) == "off"))
      refine.enabled = std::string(argv[++i]) == "on";
    else if (arg == "--refine-iterations" && i + 1 < argc)
      refine.iterations = std::atoi(argv[++i]);
    else {
      std::fprintf(
          stderr,
          "usage: %s [--backend NAME] [--renderer kernel|gl|cpu] [--particles N[,N...]] [--resolution WxH[,...]] "
          "[--frames N] [--refine on|off] [--refine-iterations N]\n",
          argv[0]);
      return 2;
    }
  }
  std::vector<Case> cases;
  if (particles.empty() && resolutions.empty()) {
    cases = {{80, 60, 200}, {640, 480, 50}};
  } else {
    for (const auto& r : bench::split(resolutions.empty() ? "80x60" : resolutions))
      for (const auto& p : bench::split(particles.empty() ? "200" : particles)) {
        Case c{};
        if (std::sscanf(r.c_str(), "%dx%d", &c.width, &c.height) != 2) {
          std::fprintf(stderr, "bad resolution '%s'\n", r.c_str());
          return 2;
        }
        c.particles = std::atoi(p.c_str());
        cases.push_back(c);
      }
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
    return failed == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "depthtrack_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
