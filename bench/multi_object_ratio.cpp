#include "multi_object_ratio.hpp"

#include <depthtrack/device.hpp>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/multi_tracker.hpp>
#include <depthtrack/sequence.hpp>
#include <depthtrack/synth.hpp>
#include <filesystem>
#include <numeric>
#include <vector>

#include "bench_rows.hpp"
#include "core/stopwatch.hpp"

namespace depthtrack::bench {

namespace {

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;  // the objects, in order
  std::vector<Pose> starts;  // each object's start
  Camera camera;
  std::vector<DepthImage> frames;
  std::vector<double> timestamps;
};

// The clip's frame i of a run of `frames` that plays it forth and back (0..n-1, n-2..0, 1..n-1, ...): a
// ten-frame clip then gives a run long enough for the median to be of the tracking after the start's
// transient (the estimate's first frames' moves, its state window's growth), not of the transient.
size_t forth_and_back(size_t i, size_t n) {
  if (n < 2) return 0;
  const size_t period = 2 * (n - 1), k = i % period;
  return k < n ? k : period - k;
}

// ycbv-0000's three objects (as scripts/gpu/multi.sh tracked them), `frames` frames of its clip played
// forth and back, one frame period apart; false when the data folder lacks them.
bool load_ycbv(Scene& scene, int frames) {
  const auto clip = data_dir() / "sequences/ycbv-0000";
  const char* const names[] = {"009_gelatin_box", "025_mug", "061_foam_brick"};
  for (const char* name : names)
    if (!std::filesystem::exists(data_dir() / "meshes/ycb" / (std::string(name) + ".obj"))) return false;
  if (!std::filesystem::exists(clip / "gt.json")) return false;
  scene.name = "ycbv0000";
  for (const char* name : names) {
    const Sequence sequence = load_sequence(clip, name);
    scene.meshes.push_back(Mesh::load(data_dir() / "meshes/ycb" / (std::string(name) + ".obj")));
    scene.starts.push_back(perturb_pose(*sequence.frames.front().ground_truth,
                                        scene.meshes.back().centre().cast<double>(), 0.01, 5, TrackerConfig{}.seed));
    if (scene.frames.empty()) {
      scene.camera = sequence.camera;
      const size_t n = sequence.frames.size();
      std::vector<DepthImage> depths;
      for (size_t i = 0; i < n; ++i) depths.push_back(sequence.load_depth(i));
      const double t0 = sequence.frames.front().timestamp;
      const double period = n > 1 ? (sequence.frames.back().timestamp - t0) / static_cast<double>(n - 1) : 1.0 / 30;
      for (size_t i = 0; i < static_cast<size_t>(frames); ++i) {
        scene.frames.push_back(depths[forth_and_back(i, n)]);
        scene.timestamps.push_back(t0 + period * static_cast<double>(i));
      }
    }
  }
  return true;
}

// The bench mesh three times: at the synthetic sequence's start and 6 cm to either side of it.
void synthetic(Scene& scene, int frames) {
  const Mesh mesh = bench_mesh(scene.name);
  SynthConfig synth;
  synth.frames = frames;
  synth.occluder_fraction = 0.3;
  const Synthesizer source(mesh, synth);
  scene.camera = synth.camera;
  for (const double dx : {0.0, -0.06, 0.06}) {
    Pose start = source.ground_truth(0.0);
    start.translation.x() += dx;
    scene.meshes.push_back(mesh);
    scene.starts.push_back(start);
  }
  for (int i = 0; i < frames; ++i) {
    SynthFrame f = source.frame(i);
    scene.frames.push_back(std::move(f.depth));
    scene.timestamps.push_back(f.timestamp);
  }
}

// The median of each of MultiTracker::update's stages over the frames after the first two (each frame's
// MultiStageTimings), and sums over the objects of their own steps: the depth's upload, the confidence
// (what the stage's wall time would be one object after another) and the filter's steps (propagate,
// render, weigh, resample, refine: device event times on a compute backend, which overlap across objects),
// and of those the atlas' drawing alone (render).
struct StageMedians {
  double frame = 0;  // the whole update, timed outside it
  std::vector<std::pair<std::string, double>> stages;
};

// The scene's objects first .. first + objects - 1 in one MultiTracker.
StageMedians median_frame(const Scene& scene, size_t first, size_t objects, bool mutual_occlusion,
                          const TrackerConfig& config, std::string& device, int host_threads = 0) {
  const auto begin = scene.meshes.begin() + static_cast<std::ptrdiff_t>(first);
  const std::vector<Mesh> meshes(begin, begin + static_cast<std::ptrdiff_t>(objects));
  MultiTracker tracker(Device::open(config.backend), meshes, scene.camera, config, mutual_occlusion, host_threads);
  for (size_t j = 0; j < objects; ++j) tracker.initialize(j, scene.starts[first + j], {0.01, 0.05});
  std::vector<double> frame, working, occluders, masks, enqueue, upload, collect, confidence, confidence_sum,
      device_sum, render_sum;
  std::vector<std::vector<double>> object_enqueue(objects);
  for (size_t i = 0; i < scene.frames.size(); ++i) {
    const Stopwatch clock;
    const std::vector<Estimate> estimates = tracker.update(scene.frames[i], scene.timestamps[i]);
    const double ms = clock.elapsed_ms();
    if (i < 2) continue;
    const MultiStageTimings& t = tracker.last_timings();
    frame.push_back(ms);
    working.push_back(t.working_ms);
    occluders.push_back(t.occluders_ms);
    masks.push_back(t.masks_ms);
    enqueue.push_back(t.enqueue_ms);
    for (size_t j = 0; j < objects && j < t.object_enqueue_ms.size(); ++j) object_enqueue[j].push_back(t.object_enqueue_ms[j]);
    collect.push_back(t.collect_ms);
    confidence.push_back(t.confidence_ms);
    double uploads = 0, confidences = 0, steps = 0, renders = 0;
    for (const Estimate& e : estimates) {
      const StepTimings& o = e.timings;
      uploads += o.upload_ms;
      confidences += o.confidence_ms;
      steps += o.propagate_ms + o.render_ms + o.weigh_ms + o.resample_ms + o.refine_ms;
      renders += o.render_ms;
    }
    render_sum.push_back(renders);
    upload.push_back(uploads);
    confidence_sum.push_back(confidences);
    device_sum.push_back(steps);
  }
  device = tracker.tracker(0).backend_description();
  StageMedians m;
  m.frame = median(frame);
  for (const auto& [name, samples] : {std::pair{"working", &working},
                                      {"occluders", &occluders},
                                      {"masks", &masks},
                                      {"enqueue", &enqueue},
                                      {"upload_sum", &upload},
                                      {"collect", &collect},
                                      {"confidence", &confidence},
                                      {"confidence_sum", &confidence_sum},
                                      {"steps_sum", &device_sum},
                                      {"render_sum", &render_sum}})
    m.stages.emplace_back(name, median(*samples));
  // Each object's start: whether a later object's costs more while the earlier ones run on the device.
  for (size_t j = 0; j < objects; ++j)
    if (!object_enqueue[j].empty()) m.stages.emplace_back("enqueue_object" + std::to_string(j), median(object_enqueue[j]));
  return m;
}

}  // namespace

void run_multi_object_ratio(const std::string& backend, const std::string& renderer, int particles, int frames,
                            double simplify_error, bool step_timings, RefineLayout refine_layout) {
  Scene scene;
  if (!load_ycbv(scene, frames)) synthetic(scene, frames);
  TrackerConfig config;
  config.backend = backend;
  config.renderer = renderer_from_string(renderer);
  config.particles = particles;
  config.width = 80;
  config.height = 60;
  config.simplify_error = simplify_error;
  config.refine.layout = refine_layout;
  // Untimed as a tracker runs by default; timed, the steps' sums (steps_sum, render_sum) are device times.
  config.step_timings = step_timings;
  const bool host = backend == "reference" || backend == "cpu" || backend.rfind("cpu:", 0) == 0;
  std::string device;
  const StageMedians one = median_frame(scene, 0, 1, false, config, device);
  // Each of the three alone: the objects differ (at 0.5 mm a 3,196-triangle mug against a 234-triangle box),
  // so "one object's time" is also read as the mean of the three's.
  std::vector<double> alone{one.frame};
  for (size_t j = 1; j < scene.meshes.size(); ++j) alone.push_back(median_frame(scene, j, 1, false, config, device).frame);
  const double alone_mean = std::accumulate(alone.begin(), alone.end(), 0.0) / static_cast<double>(alone.size());
  const std::string platform = host ? "cpu" : backend;
  const std::string name = host ? cpu_name() : device;
  for (const bool occlusion : {false, true}) {
    const StageMedians three = median_frame(scene, 0, 3, occlusion, config, device);
    const std::string test = (host ? "" : renderer + "_") + "multi_object_" + scene.name + "_80x60_" +
                             std::to_string(particles) + "p" +
                             (simplify_error > 0 ? "_simplify" + compact_number(simplify_error * 1e3) + "mm" : "") +
                             (refine_layout != RefineLayout::Auto ? std::string("_") + to_string(refine_layout) : "") +
                             "_occlusion_" + (occlusion ? "on" : "off") + (step_timings ? "" : "_untimed");
    print_row({backend, platform, name, "-", test, "one_object_ms", "ms", one.frame});
    print_row({backend, platform, name, "-", test, "three_objects_ms", "ms", three.frame});
    print_row({backend, platform, name, "-", test, "multi_object_ratio", "x", three.frame / one.frame});
    for (size_t j = 0; j < alone.size(); ++j)
      print_row({backend, platform, name, "-", test, "object" + std::to_string(j) + "_alone_ms", "ms", alone[j]});
    print_row({backend, platform, name, "-", test, "one_object_mean_ms", "ms", alone_mean});
    print_row({backend, platform, name, "-", test, "multi_object_ratio_to_mean", "x", three.frame / alone_mean});
    // The same three on the calling thread alone (MultiTracker's host_threads 1): what the thread pool gains.
    const StageMedians serial = median_frame(scene, 0, 3, occlusion, config, device, 1);
    print_row({backend, platform, name, "-", test, "three_objects_one_host_thread_ms", "ms", serial.frame});
    print_row({backend, platform, name, "-", test, "one_host_thread_ratio", "x", serial.frame / one.frame});
    // Where the time goes: each stage's median, one object's run and three objects'.
    for (const auto& [label, run] : {std::pair{"one_object_", &one}, {"three_objects_", &three}})
      for (const auto& [stage, ms] : run->stages)
        print_row({backend, platform, name, "-", test, std::string(label) + stage + "_ms", "ms", ms});
  }
}

}  // namespace depthtrack::bench
