// The sequential reference tracker: time per particle per frame, split into propagate, render,
// weigh and resample, at 80x60 and 640x480 with the handset (the thesis' object).
// Usage: depthtrack_bench_reference [--frames N] [--quick]
#include <depthtrack/synth.hpp>
#include <depthtrack/tracker.hpp>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "bench_rows.hpp"

using namespace depthtrack;

namespace {

Mesh bench_mesh(std::string& name) {
  const char* env = std::getenv("DEPTHTRACK_DATA_DIR");
  const std::filesystem::path handset = std::filesystem::path(env ? env : DEPTHTRACK_DATA_DIR) / "meshes/dbot/handset.obj";
  if (std::filesystem::exists(handset)) {
    name = "handset";
    return Mesh::load(handset);
  }
  std::fprintf(stderr, "note: %s is absent; benchmarking the built-in mesh instead\n", handset.c_str());
  name = "builtin";
  return builtin_demo_mesh();
}

void run(const Mesh& mesh, const std::string& mesh_name, int width, int height, int particles, int frames) {
  SynthConfig synth;
  synth.frames = frames;
  synth.occluder_fraction = 0.3;
  const Synthesizer scene(mesh, synth);
  TrackerConfig config;
  config.width = width;
  config.height = height;
  config.particles = particles;
  Tracker tracker(mesh, synth.camera, config);
  tracker.initialize(scene.ground_truth(0.0));
  std::vector<double> propagate, render, weigh, resample, total;
  for (int i = 0; i < frames; ++i) {
    const SynthFrame f = scene.frame(i);
    const Estimate e = tracker.update(f.depth, f.timestamp);
    if (i < 2) continue;  // warm-up: caches, first-frame propagation skipped
    const double per_particle_us = 1000.0 / particles;
    propagate.push_back(e.timings.propagate_ms * per_particle_us);
    render.push_back(e.timings.render_ms * per_particle_us);
    weigh.push_back(e.timings.weigh_ms * per_particle_us);
    resample.push_back(e.timings.resample_ms * per_particle_us);
    total.push_back(e.timings.total_ms * per_particle_us);
  }
  const std::string test = "reference_" + mesh_name + "_" + std::to_string(width) + "x" + std::to_string(height) +
                           "_" + std::to_string(particles) + "p";
  const std::string cpu = bench::cpu_name();
  for (const auto& [metric, samples] : {std::pair{"propagate", &propagate}, {"render", &render}, {"weigh", &weigh},
                                        {"resample", &resample}, {"total", &total}})
    bench::print_row({"reference", "cpu", cpu, "-", test, std::string(metric) + "_per_particle", "us", bench::median(*samples)});
  bench::print_row({"reference", "cpu", cpu, "-", test, "frames_per_second", "Hz",
                    1e6 / (bench::median(total) * particles)});
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 30;
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc) frames = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--quick")) quick = true;
    else {
      std::fprintf(stderr, "usage: %s [--frames N] [--quick]\n", argv[0]);
      return 2;
    }
  }
  try {
    std::string name;
    const Mesh mesh = bench_mesh(name);
    bench::print_header();
    run(mesh, name, 80, 60, 200, quick ? 6 : frames);
    run(mesh, name, 640, 480, quick ? 10 : 50, quick ? 4 : std::max(6, frames / 3));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "depthtrack_bench_reference: %s\n", e.what());
    return 1;
  }
  return 0;
}
