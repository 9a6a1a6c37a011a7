#include "multi_object_ratio.hpp"

#include <depthtrack/device.hpp>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/multi_tracker.hpp>
#include <depthtrack/sequence.hpp>
#include <depthtrack/synth.hpp>
#include <filesystem>
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

// ycbv-0000's three objects (as scripts/gpu-multi.sh tracked them); false when the data folder lacks them.
bool load_ycbv(Scene& scene) {
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
      for (size_t i = 0; i < sequence.frames.size(); ++i) {
        scene.frames.push_back(sequence.load_depth(i));
        scene.timestamps.push_back(sequence.frames[i].timestamp);
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

// Median ms of MultiTracker::update over the frames after the first two, for the first `objects` objects.
double median_frame_ms(const Scene& scene, size_t objects, bool mutual_occlusion, const TrackerConfig& config,
                       std::string& device) {
  const std::vector<Mesh> meshes(scene.meshes.begin(), scene.meshes.begin() + static_cast<std::ptrdiff_t>(objects));
  MultiTracker tracker(Device::open(config.backend), meshes, scene.camera, config, mutual_occlusion);
  for (size_t j = 0; j < objects; ++j) tracker.initialize(j, scene.starts[j], {0.01, 0.05});
  std::vector<double> samples;
  for (size_t i = 0; i < scene.frames.size(); ++i) {
    const Stopwatch frame;
    (void)tracker.update(scene.frames[i], scene.timestamps[i]);
    if (i >= 2) samples.push_back(frame.elapsed_ms());
  }
  device = tracker.tracker(0).backend_description();
  return median(samples);
}

}  // namespace

void run_multi_object_ratio(const std::string& backend, const std::string& renderer, int particles, int frames) {
  Scene scene;
  if (!load_ycbv(scene)) synthetic(scene, frames);
  TrackerConfig config;
  config.backend = backend;
  config.renderer = renderer_from_string(renderer);
  config.particles = particles;
  config.width = 80;
  config.height = 60;
  const bool host = backend == "reference" || backend == "cpu" || backend.rfind("cpu:", 0) == 0;
  std::string device;
  const double one = median_frame_ms(scene, 1, false, config, device);
  const std::string platform = host ? "cpu" : backend;
  const std::string name = host ? cpu_name() : device;
  for (const bool occlusion : {false, true}) {
    const double three = median_frame_ms(scene, 3, occlusion, config, device);
    const std::string test = (host ? "" : renderer + "_") + "multi_object_" + scene.name + "_80x60_" +
                             std::to_string(particles) + "p_occlusion_" + (occlusion ? "on" : "off");
    print_row({backend, platform, name, "-", test, "one_object_ms", "ms", one});
    print_row({backend, platform, name, "-", test, "three_objects_ms", "ms", three});
    print_row({backend, platform, name, "-", test, "multi_object_ratio", "x", three / one});
  }
}

}  // namespace depthtrack::bench
