// Time per frame of the tracker on one backend, split into propagate, render, hand-off, weigh, resample
// and refine (the pose refinement with the shift of the cloud; refine_share is its % of the frame,
// refine_iterations the median of the steps it tried per frame)
// and confidence (the estimate's silhouette drawn and compared on the host, for confidence and status),
// with the handset (the thesis' object) on a synthetic occluded sequence. Prints CSV rows.
// render is the atlas draw (GL waited for); handoff moves poses to GL and the atlas to the kernels.
// Usage: depthtrack_bench [--backend NAME] [--renderer kernel|gl|cpu] [--particles N[,N...]] [--resolution WxH[,...]]
//                         [--frames N] [--refine on|off] [--refine-iterations N] [--refine-converged M]
//                         [--fine-noise-scale S]
//   default: the reference at 80x60 (200 particles) and 640x480 (50 particles).
// With --multi-objects: only one object against three in one process (bench/multi_object_ratio.hpp).
// Then the off-screen start (one particle 10,000 km to the side, 5 frames), unless --no-offscreen, and global
// initialization at 80x60 (from the object's box, and from no hint), unless --no-global: the tracker's construction
// (every program built, the search's among them), the first search and the same search again.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <depthtrack/error.hpp>
#include <depthtrack/init_hint.hpp>
#include <depthtrack/synth.hpp>
#include <depthtrack/tracker.hpp>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "bench_args.hpp"
#include "bench_rows.hpp"
#include "core/stopwatch.hpp"
#include "host_memory.hpp"
#include "multi_object_ratio.hpp"

using namespace depthtrack;

namespace {

struct Case {
  int width, height, particles;
};

// How frames reach the tracker. Synthesized before the timed loop by default: drawing a frame between
// two updates is not the tracker's time, and it leaves the host's caches cold for the driver's calls.
struct Feed {
  double pace_ms = 0;              // > 0: each frame handed over this long after the last returned
  bool synthesize_inline = false;  // each frame drawn just before its update (the bench's earlier default)
};

// The reference filter and its threaded form (cpu, cpu:N) run on the host: no renderer, the CPU's name.
bool host_backend(const std::string& backend) {
  return backend == "reference" || backend == "cpu" || backend.rfind("cpu:", 0) == 0;
}

// The CPU time of every thread of this process so far: the threaded backends' workers included.
double process_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

// A case's medians: the filter's frame (total_ms) and the CPU time its updates took on all threads.
struct CaseTimes {
  double total_ms = 0, update_cpu_ms = 0;
};

// The test name's mark of a fit other than the default's stages: "_onestage", or "_fine35pc" for a second
// stage at 0.35 sigma(y); empty for the default.
std::string fit_stages_tag(const Refinement& refine) {
  if (!refine.enabled || refine.fine_noise_scale == Refinement{}.fine_noise_scale) return {};
  if (refine.fine_noise_scale == 0) return "_onestage";
  return "_fine" + std::to_string(std::lround(100 * refine.fine_noise_scale)) + "pc";
}

// Prints the case's rows; returns its medians.
// feed.pace_ms > 0: each frame is handed over that long after the one before returned, as a sensor stream
// leaves the device idle between frames (back to back, a frame's calls meet the last one's tail).
CaseTimes run(const Mesh& mesh, const std::string& mesh_name, const std::string& backend, const std::string& renderer,
              const Refinement& refine, const Case& c, int frames, const OcclusionWindow& window, double simplify_error,
              bool step_timings, const Feed& feed) {
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
  config.occlusion_window = window;
  config.simplify_error = simplify_error;
  config.step_timings = step_timings;
  // Start-up: construction (device buffers, kernels built or read from the driver's cache) and the
  // initial particle and occlusion state, with the host memory it peaks at.
  const bool peak_known = bench::reset_peak_resident();
  const Stopwatch startup;
  Tracker tracker(mesh, synth.camera, config);
  tracker.initialize(scene.ground_truth(0.0));
  const double startup_ms = startup.elapsed_ms();
  const double startup_peak_mib = peak_known ? bench::peak_resident_mib() : NAN;
  std::vector<double> propagate, render, handoff, weigh, resample, refined, confidence, upload, enqueue, wait, total,
      update, refine_steps, update_cpu, busy_threads;
  // Frames beyond 1 GiB of depth are drawn as they go (a long run at a high resolution).
  const bool inline_synthesis =
      feed.synthesize_inline || static_cast<double>(frames) * synth.camera.width * synth.camera.height * 4 > 0x1p30;
  std::vector<SynthFrame> prepared;
  if (!inline_synthesis)
    for (int i = 0; i < frames; ++i) prepared.push_back(scene.frame(i));
  for (int i = 0; i < frames; ++i) {
    const SynthFrame f = inline_synthesis ? scene.frame(i) : std::move(prepared[static_cast<size_t>(i)]);
    const double cpu_before = process_cpu_ms();
    const Stopwatch update_clock;
    const Estimate e = tracker.update(f.depth, f.timestamp);
    const double update_ms = update_clock.elapsed_ms();
    const double cpu_ms = process_cpu_ms() - cpu_before;
    if (feed.pace_ms > 0) std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(feed.pace_ms));
    if (i < 2) continue;  // warm-up: caches, first-frame propagation skipped
    propagate.push_back(e.timings.propagate_ms);
    render.push_back(e.timings.render_ms);
    handoff.push_back(e.timings.handoff_ms);
    weigh.push_back(e.timings.weigh_ms);
    resample.push_back(e.timings.resample_ms);
    refined.push_back(e.timings.refine_ms);
    refine_steps.push_back(e.refine_iterations);
    confidence.push_back(e.timings.confidence_ms);
    upload.push_back(e.timings.upload_ms);
    enqueue.push_back(e.timings.enqueue_ms);
    wait.push_back(e.timings.wait_ms);
    total.push_back(e.timings.total_ms);
    update.push_back(update_ms);
    update_cpu.push_back(cpu_ms);
    busy_threads.push_back(cpu_ms / update_ms);
  }
  const std::string device = tracker.backend_description();
  const std::string test =
      (host_backend(backend) ? "" : renderer + "_") + mesh_name + "_" + std::to_string(c.width) + "x" +
      std::to_string(c.height) + "_" + std::to_string(c.particles) + "p" +
      (refine.enabled ? "_refine" + std::to_string(refine.iterations) : "_norefine") +
      (refine.enabled && refine.layout != RefineLayout::Auto ? std::string("_") + to_string(refine.layout)
                                                             : std::string()) +
      fit_stages_tag(refine) +
      (window.is_automatic() ? std::string()
       : window.width > 0 || window.height > 0
           ? "_window" + std::to_string(window.width) + "x" + std::to_string(window.height)
           : std::string("_windowfull")) +
      (simplify_error > 0 ? "_simplify" + bench::compact_number(simplify_error * 1e3) + "mm" : std::string()) +
      (step_timings ? "" : "_untimed") +
      (feed.pace_ms > 0 ? "_paced" + bench::compact_number(feed.pace_ms) + "ms" : "") +
      (inline_synthesis ? "_inline" : "");
  const std::string platform = host_backend(backend) ? "cpu" : backend;
  const std::string name = host_backend(backend) ? bench::cpu_name() : device;
  for (const auto& [metric, samples] : {std::pair{"propagate", &propagate},
                                        {"render", &render},
                                        {"handoff", &handoff},
                                        {"weigh", &weigh},
                                        {"resample", &resample},
                                        {"refine", &refined},
                                        {"confidence", &confidence},
                                        {"upload", &upload},
                                        {"enqueue", &enqueue},
                                        {"wait", &wait},
                                        {"total", &total},
                                        {"update", &update},
                                        {"update_cpu", &update_cpu}}) {
    const double ms = bench::median(*samples);
    bench::print_row({backend, platform, name, "-", test, std::string(metric) + "_ms", "ms", ms});
    bench::print_row(
        {backend, platform, name, "-", test, std::string(metric) + "_per_particle", "us", 1000.0 * ms / c.particles});
  }
  bench::print_row(
      {backend, platform, name, "-", test, "refine_share", "%", 100.0 * bench::median(refined) / bench::median(total)});
  bench::print_row({backend, platform, name, "-", test, "refine_iterations", "steps", bench::median(refine_steps)});
  bench::print_row({backend, platform, name, "-", test, "busy_threads", "threads", bench::median(busy_threads)});
  bench::print_row({backend, platform, name, "-", test, "drawn_triangles", "triangles",
                    static_cast<double>(tracker.drawn_triangles())});
  const auto [window_width, window_height] = tracker.occlusion_window_size();
  bench::print_row({backend, platform, name, "-", test, "state_window_pixels", "pixels",
                    static_cast<double>(window_width) * window_height});
  bench::print_row({backend, platform, name, "-", test, "frames_per_second", "Hz", 1000.0 / bench::median(total)});
  bench::print_row({backend, platform, name, "-", test, "startup_ms", "ms", startup_ms});
  bench::print_row({backend, platform, name, "-", test, "startup_host_peak", "MiB", startup_peak_mib});
  return {bench::median(total), bench::median(update_cpu)};
}

const char* const kUsage =
    "usage: depthtrack_bench [--backend NAME] [--renderer kernel|gl|cpu] [--particles N[,N...]] "
    "[--resolution WxH[,...]] [--frames N] [--refine on|off] [--refine-iterations N] [--refine-converged M]\n"
    "       [--fine-noise-scale S] [--refine-layout auto|one-group|spread|one-launch] [--occlusion-window "
    "auto|full|WxH]\n"
    "       [--simplify-error M] [--mesh FILE] [--no-global] [--no-offscreen] [--multi-objects] [--untimed-steps] "
    "[--pace MS]\n"
    "       [--synthesize-inline]\n"
    "Times tracker frames on a synthetic occluded handset sequence, split into propagate / render / hand-off /\n"
    "weigh / resample, start-up (construction + initialize) with its peak host memory, and the off-screen start\n"
    "(one particle 10,000 km to the side, 5 frames); prints CSV rows\n"
    "backend,platform,device,driver,test,metric,unit,value. update_ms is depth in to pose out as the caller\n"
    "sees Tracker::update (the 640x480 frame's check and decimation included), total_ms the filter's frame,\n"
    "update_cpu_ms the CPU time of the process's threads in the update, busy_threads update_cpu_ms per\n"
    "update_ms (median of the frames').\n"
    "  --backend NAME         reference (default), cpu, cpu:N, opencl, opencl:pocl, cuda, ... (`depthtrack info`);\n"
    "                         cpu and cpu:N also time the reference on each case: speedup_over_reference, and\n"
    "                         cpu_time_over_reference (update_cpu_ms against the reference's; the speedup is\n"
    "                         about busy_threads over it: idle threads lower the one, slowed threads raise\n"
    "                         the other)\n"
    "  --renderer NAME        atlas renderer of device backends: kernel (default), gl, cpu\n"
    "  --particles N[,N...]   particle counts (default 200)\n"
    "  --resolution WxH[,...] working resolutions (default 80x60)\n"
    "  --frames N             frames per case, the first two not timed (default 20, at least 4)\n"
    "  --refine on|off        the pose refinement (default on; refine_share is its % of the frame)\n"
    "  --refine-iterations N  refinement steps per frame at most (default: TrackerConfig's)\n"
    "  --refine-converged M   the refinement stops when a step would move the mesh less than M metres\n"
    "                         (default: TrackerConfig's; 0 takes every step)\n"
    "  --fine-noise-scale S   the fit's second stage at S times sigma(y), 0 for one stage (default:\n"
    "                         TrackerConfig's)\n"
    "  --refine-layout NAME   device backends' refinement: auto (default: spread on CUDA, for meshes of\n"
    "                         2,048 triangles or more and on GPUs over 160x120, else one-launch), one-group,\n"
    "                         spread or one-launch;\n"
    "                         a given one is named in the test column\n"
    "  --occlusion-window W   particles keep occlusion state in a window around the estimate: auto (default:\n"
    "                         sized to the object; TrackerConfig::occlusion_window), full (the whole image) or\n"
    "                         WxH; full and WxH are named in the test column\n"
    "  --simplify-error M     draw the mesh simplified to within M metres of its surface (default 0: as given,\n"
    "                         not TrackerConfig::simplify_error's 0.0005), named in the test column; also\n"
    "                         --multi-objects'\n"
    "  --mesh FILE            track this mesh instead of the handset (e.g. a 16k-triangle YCB mesh)\n"
    "  --untimed-steps        as a tracker runs by default: the device does not time each step\n"
    "                         (TrackerConfig::step_timings off: the steps' rows read 0, total_ms without the\n"
    "                         timing records), named in the test column; otherwise every step is timed\n"
    "  --pace MS              hand each frame over MS milliseconds after the last one returned, as a sensor\n"
    "                         stream does (the device idles between frames; back to back, each frame's calls\n"
    "                         meet the last one's work still running): total_ms is then the latency a tracker\n"
    "                         fed at sensor rate sees; named in the test column\n"
    "  --synthesize-inline    draw each synthetic frame just before its update (the bench's earlier default),\n"
    "                         not all before the timed frames; named in the test column\n"
    "  --no-global            leave out the global initialization rows (box hint and no hint, 80x60)\n"
    "  --no-offscreen         leave out the off-screen start's rows (its updates are not the cases' frames)\n"
    "  --multi-objects        instead: one object against three in one process at 80x60 (ycbv-0000's, else\n"
    "                         the handset thrice), mutual occlusion off and on: multi_object_ratio rows (and\n"
    "                         multi_object_ratio_to_mean, over the three objects alone; --refine-layout as\n"
    "                         for one object);\n"
    "                         --particles N each (default 2000); --frames N frames (ycbv-0000's ten-frame\n"
    "                         clip played forth and back); --untimed-steps as for one object\n"
    "Without --particles and --resolution: the reference at 80x60 (200 particles) and 640x480 (50).\n";

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
       {std::pair{"box", projected_box(mesh, synth.camera, f.ground_truth)}, std::pair{"none", InitHint::anywhere()}}) {
    // Construction builds every program, the search's scoring kernels among them (CUDA compiles
    // them with NVRTC, OpenCL reads the driver's cache): printed apart from the search itself.
    const Stopwatch construct;
    Tracker tracker(mesh, synth.camera, config);
    const double construct_ms = construct.elapsed_ms();
    const Estimate e = tracker.initialize_global(f.depth, f.timestamp, hint);
    // The same search again on the warm tracker: what recovery pays per search.
    const Estimate again = tracker.initialize_global(f.depth, f.timestamp, hint);
    const std::string test = std::string("global_init_") + start + "_" + mesh_name + "_80x60";
    const std::string platform = host_backend(backend) ? "cpu" : backend;
    const std::string name = host_backend(backend) ? bench::cpu_name() : tracker.backend_description();
    bench::print_row({backend, platform, name, "-", test, "construct_ms", "ms", construct_ms});
    bench::print_row({backend, platform, name, "-", test, "search_ms", "ms", e.timings.search_ms});
    bench::print_row({backend, platform, name, "-", test, "search_again_ms", "ms", again.timings.search_ms});
    bench::print_row(
        {backend, platform, name, "-", test, "poses_scored", "poses", static_cast<double>(e.search_poses)});
    bench::print_row({backend, platform, name, "-", test, "poses_per_second", "1/s",
                      1000.0 * static_cast<double>(e.search_poses) / e.timings.search_ms});
    bench::print_row({backend, platform, name, "-", test, "error_after_first_frame", "mm",
                      1000 * translation_error(e.pose, f.ground_truth)});
  }
}

// The off-screen start: one particle whose start projects 10,000 km to the side of an
// 80x60 image, as `track --init "1e7 0 0.06 1 0 0 0" --particles 1`; the rasterizers clamp its box,
// so the whole run (construction, start, `frames` frames) takes well under a second where it once took
// minutes. The recovery's search is off (as with --no-recover): once lost (the third frame) it would
// spend its budget per frame (RecoveryModel::budget_ms) on the search, not on the off-screen pose.
// Rows: the run's wall time and its slowest frame.
void run_offscreen(const Mesh& mesh, const std::string& mesh_name, const std::string& backend,
                   const std::string& renderer, int frames) {
  SynthConfig synth;
  synth.frames = frames;
  const Synthesizer scene(mesh, synth);
  TrackerConfig config;
  config.backend = backend;
  config.renderer = renderer_from_string(renderer);
  config.particles = 1;
  config.recovery.enabled = false;
  std::vector<SynthFrame> input;  // drawn first: the synthesis is not the tracker's time
  for (int i = 0; i < frames; ++i) input.push_back(scene.frame(i));
  const Stopwatch run;
  Tracker tracker(mesh, synth.camera, config);
  tracker.initialize(Pose(Eigen::Vector3d(1e7, 0, 0.06), Eigen::Quaterniond::Identity()));
  double slowest_ms = 0;
  for (const SynthFrame& f : input) {
    const Stopwatch frame;
    (void)tracker.update(f.depth, f.timestamp);
    slowest_ms = std::max(slowest_ms, frame.elapsed_ms());
  }
  const double run_ms = run.elapsed_ms();
  const std::string test = (host_backend(backend) ? "" : renderer + "_") + mesh_name + "_offscreen_start_80x60_1p_" +
                           std::to_string(frames) + "frames";
  const std::string platform = host_backend(backend) ? "cpu" : backend;
  const std::string name = host_backend(backend) ? bench::cpu_name() : tracker.backend_description();
  bench::print_row({backend, platform, name, "-", test, "run_ms", "ms", run_ms});
  bench::print_row({backend, platform, name, "-", test, "slowest_frame_ms", "ms", slowest_ms});
}

}  // namespace

int main(int argc, char** argv) {
  std::string backend = "reference", renderer = "kernel";
  std::vector<int> particle_counts;
  std::vector<std::pair<int, int>> sizes;
  int frames = 20;
  Refinement refine;
  OcclusionWindow window;
  // The mesh as given (not TrackerConfig's 0.5 mm): the rows compare with earlier sessions' and the meshes'
  // triangle counts are what they time; --simplify-error times the tracker's default.
  double simplify_error = 0;
  bool global = true, offscreen = true, multi_objects = false, step_timings = true;
  Feed feed;
  std::string mesh_file;
  const auto option = [&](const std::string& arg, bench::ArgReader& args) {
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
    else if (arg == "--refine-converged")
      refine.converged_motion = bench::parse_nonnegative_double(args.value(), arg);
    else if (arg == "--fine-noise-scale")
      refine.fine_noise_scale = bench::parse_nonnegative_double(args.value(), arg);
    else if (arg == "--refine-layout")
      try {
        refine.layout = refine_layout_from_string(args.value());
      } catch (const InputError& e) {
        throw bench::UsageError{e.what()};
      }
    else if (arg == "--occlusion-window")
      try {
        window = occlusion_window_from_string(args.value());
      } catch (const InputError& e) {
        throw bench::UsageError{arg + ": " + e.what()};
      }
    else if (arg == "--simplify-error")
      simplify_error = bench::parse_nonnegative_double(args.value(), arg);
    else if (arg == "--mesh")
      mesh_file = args.value();
    else if (arg == "--no-global")
      global = false;
    else if (arg == "--no-offscreen")
      offscreen = false;
    else if (arg == "--untimed-steps")
      step_timings = false;
    else if (arg == "--pace")
      feed.pace_ms = bench::parse_nonnegative_double(args.value(), arg);
    else if (arg == "--synthesize-inline")
      feed.synthesize_inline = true;
    else if (arg == "--multi-objects")
      multi_objects = true;
    else
      throw bench::UsageError{"unknown option '" + arg + "'"};
  };
  if (const int status = bench::parse_command_line(argc, argv, "depthtrack_bench", kUsage, option); status >= 0)
    return status;
  if (multi_objects) {
    try {
      bench::print_header();
      for (const int p : particle_counts.empty() ? std::vector<int>{2000} : particle_counts)
        bench::run_multi_object_ratio(backend, renderer, p, std::max(frames, 4), simplify_error, step_timings,
                                      refine.layout);
      return 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "depthtrack_bench: %s\n", e.what());
      return 1;
    }
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
    const Mesh mesh = mesh_file.empty() ? bench::bench_mesh(name) : Mesh::load(mesh_file);
    if (!mesh_file.empty()) name = std::filesystem::path(mesh_file).stem().string();
    bench::print_header();
    int failed = 0;
    for (const Case& c : cases) {
      // A case the device cannot run (too many particles for its memory) gets a status row, and
      // the others still run.
      try {
        const CaseTimes times = run(mesh, name, backend, renderer, refine, c, std::max(frames, 4), window,
                                    simplify_error, step_timings, feed);
        // The threaded CPU path is worth its name only against the sequential reference, measured
        // here in the same run on the same case: the speedup row.
        if (backend != "reference" && host_backend(backend)) {
          const CaseTimes reference = run(mesh, name, "reference", renderer, refine, c, std::max(frames, 4), window,
                                          simplify_error, step_timings, feed);
          const std::string test = name + "_" + std::to_string(c.width) + "x" + std::to_string(c.height) + "_" +
                                   std::to_string(c.particles) + "p";
          bench::print_row({backend, "cpu", bench::cpu_name(), "-", test, "speedup_over_reference", "x",
                            reference.total_ms / times.total_ms});
          // The speedup is busy_threads over this ratio: a thread idle (a serial step, a wait) lowers the
          // first, a thread slowed (a shared core, a lower clock, contended memory) raises this one.
          bench::print_row({backend, "cpu", bench::cpu_name(), "-", test, "cpu_time_over_reference", "x",
                            times.update_cpu_ms / reference.update_cpu_ms});
        }
      } catch (const Error& e) {
        ++failed;
        const std::string test = renderer + "_" + name + "_" + std::to_string(c.width) + "x" +
                                 std::to_string(c.height) + "_" + std::to_string(c.particles) + "p";
        bench::print_status(backend, test, e.what());
      }
    }
    if (offscreen) {
      try {
        run_offscreen(mesh, name, backend, renderer, 5);
      } catch (const Error& e) {
        ++failed;
        bench::print_status(backend, name + "_offscreen_start_80x60_1p", e.what());
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
