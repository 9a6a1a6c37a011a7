#include "cli/bench_suite.hpp"

#include <cmath>
#include <depthtrack/tracker.hpp>
#include <optional>

#include "bench_rows.hpp"
#include "cli/environment_defaults.hpp"
#include "cli/step_bytes.hpp"
#include "compute/queue.hpp"
#include "core/stopwatch.hpp"
#include "filter/frame_plan.hpp"
#include "model/fit_noise.hpp"
#include "tracker/make_filter_backend.hpp"

namespace depthtrack::cli {

BenchGrid quick_grid() {
  return {{50, 200, 800}, {{80, 60}, {160, 120}, {320, 240}, {640, 480}}, 20, 50, 200, 200, 12, 1e7};
}

BenchGrid full_grid() {
  // 200 and 2000 particles are where the reference also runs (the speedup); 1,500,000 and the latency
  // at 2,000 are the throughput and latency targets.
  return {{200, 2000, 10000, 100000, 300000, 1000000, 1500000},
          {{80, 60}, {160, 120}, {320, 240}, {640, 480}},
          10000,
          10000,
          100000,
          2000,
          20,
          2e7};
}

BenchGrid test_grid() {
  return {{10, 30}, {{80, 60}, {160, 120}}, 10, 10, 10, 10, 3, 1e6};
}

BenchMesh make_bench_mesh(const std::string& name, Mesh mesh, int frames) {
  SynthConfig synth;
  synth.frames = frames;
  synth.occluder_fraction = 0.3;
  const Synthesizer scene(mesh, synth);
  BenchMesh m{name, std::move(mesh), {}};
  for (int i = 0; i < frames; ++i) m.frames.push_back(scene.frame(i));
  return m;
}

BenchTarget describe_target(const std::string& backend) {
  if (backend == "reference") return {backend, "cpu", bench::cpu_name(), "-", true, false};
  // The reference on a thread pool (cpu, cpu:N): no compute device to open; the count is checked here.
  if (backend == "cpu" || backend.rfind("cpu:", 0) == 0)
    return {backend, "cpu", bench::cpu_name() + ", " + std::to_string(cpu_backend_threads(backend)) + " threads",
            "-",     true,  false};
  const auto queue = compute::open_device(backend);
  const compute::DeviceInfo& info = queue->info();
  return {backend, info.platform, info.name, info.driver, !info.is_gpu, true, info};
}

std::string BenchCase::test() const {
  return sweep + "_" + mesh->name + "_" + std::to_string(width) + "x" + std::to_string(height) + "_" +
         std::to_string(particles) + "p_" + to_string(mode) + (step_timings ? "" : "_untimed");
}

std::vector<BenchCase> grid_cases(const BenchGrid& grid, const std::vector<BenchMesh>& meshes) {
  std::vector<BenchCase> cases;
  const BenchMesh* first = &meshes.front();
  for (const int p : grid.particle_counts) cases.push_back({"particles", first, 80, 60, p});
  for (const auto& [w, h] : grid.resolutions)
    cases.push_back({"resolution", first, w, h, grid.particles_at_resolution});
  for (const BenchMesh& m : meshes) cases.push_back({"triangles", &m, 80, 60, grid.particles_at_triangles});
  for (const auto mode : {OcclusionStorage::PerPixelTime, OcclusionStorage::GlobalTime, OcclusionStorage::Off})
    cases.push_back({"occlusion", first, 80, 60, grid.particles_at_occlusion, mode});
  cases.push_back({"latency", first, 80, 60, grid.particles_at_latency, OcclusionStorage::PerPixelTime, false});
  return cases;
}

CaseResult run_case(const BenchCase& c, const BenchTarget& target, const std::string& renderer, int frames,
                    const std::string& commit, double reference_ms, std::vector<BenchRow>& rows) {
  TrackerConfig config;
  config.step_timings = c.step_timings;  // the per-step split is what the sweeps print
  config.backend = target.backend;
  config.renderer = renderer_from_string(renderer);
  config.gl_path = gl_path_from_environment();  // as demo and track take it (the library reads no environment)
  config.width = c.width;
  config.height = c.height;
  config.particles = c.particles;
  config.occlusion_storage = c.mode;
  config.simplify_error = 0;  // the meshes as given: time against triangle count is one of the sweeps
  const auto& seq = c.mesh->frames;
  Tracker tracker(c.mesh->mesh, Camera::make(640, 480, 525.0, 525.0, 319.5, 239.5), config);
  tracker.initialize(seq.front().ground_truth);
  std::vector<double> steps[6], total, latency;
  for (int i = 0; i < frames && i < static_cast<int>(seq.size()); ++i) {
    const Stopwatch update;
    const Estimate e = tracker.update(seq[static_cast<size_t>(i)].depth, seq[static_cast<size_t>(i)].timestamp);
    const double update_ms = update.elapsed_ms();
    if (i < 2) continue;  // warm-up: caches, and the first frame has no propagation
    latency.push_back(update_ms);
    const StepTimings& t = e.timings;
    const double ms[6] = {t.propagate_ms, t.render_ms, t.handoff_ms, t.weigh_ms, t.resample_ms, t.refine_ms};
    for (int s = 0; s < 6; ++s) steps[s].push_back(ms[s]);
    total.push_back(t.total_ms);
  }
  const std::string test = c.test();
  auto row = [&](const std::string& metric, const std::string& unit, double median, double p95, size_t samples) {
    rows.push_back({target.backend, target.platform, target.device, target.driver, commit, test, metric, unit, median,
                    p95, static_cast<int>(samples)});
  };
  const size_t pixels = static_cast<size_t>(c.width) * static_cast<size_t>(c.height);
  // The frame the device filter ran: its plan, as the filter made it.
  std::optional<FramePlan> plan;
  if (target.on_device)
    plan = make_frame_plan(config, target.info, frame_sizes(c.mesh->mesh, tracker.working_camera(), config));
  const bool inside_weigh = plan && plan->weigh == WeighStep::RenderWeigh;
  // The occlusion state the filter kept: its (automatic) window at the last frame.
  const auto [window_width, window_height] = tracker.occlusion_window_size();
  const size_t state_pixels = static_cast<size_t>(window_width) * static_cast<size_t>(window_height);
  const bool weigh_propagates = plan && plan->propagate_in_weigh;
  const StepBytes b = step_bytes(
      static_cast<size_t>(c.particles), pixels, c.mode, target.on_device && renderer == "gl",
      config.refine.enabled ? config.refine.iterations * static_cast<int>(model::fit_stages(config).size()) : 0,
      inside_weigh, state_pixels, weigh_propagates);
  const char* names[6] = {"propagate", "render", "handoff", "weigh", "resample", "refine"};
  const double bytes[6] = {b.propagate, b.render, b.handoff, b.weigh, b.resample, b.refine};
  for (int s = 0; s < 6; ++s) {
    const double ms = median_of(steps[s]);
    row(std::string(names[s]) + "_ms", "ms", ms, p95_of(steps[s]), steps[s].size());
    row(std::string(names[s]) + "_bytes", "MB", bytes[s] / 1e6, bytes[s] / 1e6, 1);
    row(std::string(names[s]) + "_bandwidth", "GB/s", ms > 0 ? bytes[s] / (ms * 1e6) : NAN, NAN, steps[s].size());
  }
  const double frame_ms = median_of(total), frame_p95 = p95_of(total);
  row("frame_ms", "ms", frame_ms, frame_p95, total.size());
  row("frames_per_second", "Hz", 1000 / frame_ms, 1000 / frame_p95, total.size());
  row("latency_ms", "ms", median_of(latency), p95_of(latency), latency.size());
  CaseResult result{c, target.backend, frame_ms, NAN};
  if (target.on_device) {
    // The kernel renderer's atlas as the filter sizes it; the GL and cpu renderers' holds every particle's tile.
    const size_t particles = static_cast<size_t>(c.particles);
    const size_t atlas_tiles = config.renderer == Renderer::Kernel ? plan->atlas_tiles : particles;
    result.memory_mib = filter_memory_mib(particles, pixels, c.mode, atlas_tiles, state_pixels);
    row("device_memory", "MiB", result.memory_mib, result.memory_mib, 1);
    row("state_window_pixels", "pixels", static_cast<double>(state_pixels), static_cast<double>(state_pixels), 1);
  }
  if (target.backend != "reference" && std::isfinite(reference_ms))
    row("speedup_vs_reference", "x", reference_ms / frame_ms, NAN, total.size());
  return result;
}

}  // namespace depthtrack::cli
