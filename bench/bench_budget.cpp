// Accuracy against time per frame on any backend, for fixed particle counts and for frame budgets
// (TrackerConfig::budget_ms): mean ADD-S over each YCB-Video clip's objects (ycbv-0000, ycbv-0049) and on
// the synthetic occluded handset, with the frame time's median and 95th percentile and the mean count.
// Starts from ground truth moved by 1 cm and 5 degrees (as tests/eval/test_accuracy.cpp), at 80x60.
// The frame time is the tracker's (Estimate::timings.total_ms: filter, confidence and a lost track's search;
// frame_p95_without_search leaves the search out, as the budget does: it has its own; frame_p95_budgeted
// also leaves out the first frame after initialize, which runs a search's budget by design, and pools
// the seeds of --seeds, so that a 20-frame clip's 95th percentile is not its largest frame); latency adds the
// decimation of the 640x480 frame; png_decode_ms is a depth PNG's decoding (the reading path, on a reader
// thread beside the tracker in track_sequence; here done before each clip's tracking); update_cpu_* is the
// thread CPU time of Tracker::update (decimation included), which other processes on the core do not
// lengthen (on a device backend, the host's share of the frame). Prints CSV rows.
//   depthtrack_bench_budget [--backend reference,cpu,cuda,...] [--particles 200,50,20] [--budget-ms 5,10]
//                           [--max-particles N] [--synthetic-frames N] [--objects NAME,...] [--seed N]
//                           [--seeds N]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <depthtrack/device.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/synth.hpp>
#include <filesystem>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "bench_rows.hpp"
#include "core/stopwatch.hpp"

using namespace depthtrack;

namespace {

struct Setting {
  int particles = 200;   // the fixed count, or a budget's most (--max-particles)
  double budget_ms = 0;  // 0: the fixed count
  // A budget's name carries its most where it is not the default 200.
  std::string name() const {
    if (!(budget_ms > 0)) return std::to_string(particles) + "p";
    return "budget" + bench::compact_number(budget_ms) + "ms" +
           (particles == kDefaultMostParticles ? "" : "_max" + std::to_string(particles) + "p");
  }
  static constexpr int kDefaultMostParticles = 200;
};

// Where a backend runs, for the rows' platform and device columns: the host's CPU, or the compute
// device the selector opens.
struct Where {
  std::string platform, device;
};

Where where_of(const std::string& backend) {
  const std::shared_ptr<Device> device = Device::open(backend);
  if (device->is_host()) return {"cpu", bench::cpu_name()};
  return {backend, device->name()};
}

struct Outcome {
  std::vector<double> adds_mm, frame_ms, tracked_ms, latency_ms, particles;
  // Frames whose count the budget chose: not the first after initialize (it runs a search's budget, as
  // ParticleBudget::next_initial says), none that searched.
  std::vector<double> budgeted_ms;
  std::vector<double> cpu_ms;  // the calling thread's CPU time in Tracker::update, frames without a search
};

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t k = static_cast<size_t>(std::ceil(q * static_cast<double>(v.size()))) - 1;
  return v[std::min(k, v.size() - 1)];
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? NAN : s / static_cast<double>(v.size());
}

// The objects each clip's ground truth holds.
std::vector<std::string> clip_objects(const std::filesystem::path& clip) {
  if (clip.filename() == "ycbv-0000") return {"009_gelatin_box", "025_mug", "061_foam_brick"};
  return {"004_sugar_box", "007_tuna_fish_can", "010_potted_meat_can", "024_bowl"};
}

TrackerConfig config_for(const std::string& backend, const Setting& s, uint64_t seed) {
  TrackerConfig config;
  config.backend = backend;
  config.seed = seed;
  config.particles = s.particles;  // with a budget, the most a frame runs
  config.budget_ms = s.budget_ms;
  return config;
}

// The calling thread's CPU time (ms): unlike the wall clock, not lengthened by other processes taking the
// core (on a loaded machine most of a frame's 95th percentile); the reference backend runs on this thread.
double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

void add_frame(Outcome& o, const Estimate& e, double adds_m, double latency_ms, double cpu_ms, bool first) {
  if (e.timings.search_ms == 0) o.cpu_ms.push_back(cpu_ms);
  if (e.timings.search_ms == 0 && !first) o.budgeted_ms.push_back(e.timings.total_ms);
  o.adds_mm.push_back(1000 * adds_m);
  o.frame_ms.push_back(e.timings.total_ms);
  o.tracked_ms.push_back(e.timings.total_ms - e.timings.search_ms);  // what the budget covers
  o.latency_ms.push_back(latency_ms);
  o.particles.push_back(e.particles);
}

// One object of a clip, from ground truth moved by 1 cm and 5 degrees. Every depth PNG is decoded before
// the tracking starts (png_decode_ms is their decoding): on one core a reader thread decoding beside the
// tracker (track_sequence) would be timed as part of the frames it interrupts.
void track_clip_object(const std::filesystem::path& clip, const std::string& object, const TrackerConfig& config,
                       Outcome& o) {
  const Mesh mesh = Mesh::load(bench::data_dir() / "meshes/ycb" / (object + ".obj"));
  const Sequence sequence = load_sequence(clip, object);
  std::vector<DepthImage> depths;
  for (size_t i = 0; i < sequence.frames.size(); ++i) depths.push_back(sequence.load_depth(i));
  const AddsMetric adds(mesh);
  Tracker tracker(mesh, sequence.camera, config);
  const Pose& truth0 = *sequence.frames.front().ground_truth;
  tracker.initialize(perturb_pose(truth0, mesh.centre().cast<double>(), 0.01, 5.0, 1),
                     InitialSpread{0.01, 5.0 * std::numbers::pi / 180});
  for (size_t i = 0; i < depths.size(); ++i) {
    const Stopwatch clock;
    const double cpu = thread_cpu_ms();
    const Estimate e = tracker.update(depths[i], sequence.frames[i].timestamp);
    add_frame(o, e, adds(e.pose, *sequence.frames[i].ground_truth), clock.elapsed_ms(), thread_cpu_ms() - cpu, i == 0);
  }
}

void track_synthetic(const Mesh& mesh, const std::vector<SynthFrame>& frames, const SynthConfig& synth,
                     const TrackerConfig& config, Outcome& o) {
  const AddsMetric adds(mesh);
  Tracker tracker(mesh, synth.camera, config);
  const Pose start = perturb_pose(frames.front().ground_truth, mesh.centre().cast<double>(), 0.01, 5.0, 1);
  tracker.initialize(start, InitialSpread{0.01, 5.0 * std::numbers::pi / 180});
  for (const SynthFrame& f : frames) {
    const Stopwatch clock;
    const double cpu = thread_cpu_ms();
    const Estimate e = tracker.update(f.depth, f.timestamp);
    add_frame(o, e, adds(e.pose, f.ground_truth), clock.elapsed_ms(), thread_cpu_ms() - cpu, &f == &frames.front());
  }
}

// The share of frames longer than budget_ms (NaN without a budget).
double over_share(const std::vector<double>& ms, double budget_ms) {
  if (!(budget_ms > 0) || ms.empty()) return NAN;
  return static_cast<double>(std::count_if(ms.begin(), ms.end(), [&](double t) { return t > budget_ms; })) /
         static_cast<double>(ms.size());
}

void print(const std::string& backend, const Where& where, const std::string& test, const Outcome& o,
           double budget_ms) {
  const auto row = [&](const char* metric, const char* unit, double value) {
    bench::print_row({backend, where.platform, where.device, "-", test, metric, unit, value});
  };
  row("adds_mean", "mm", mean(o.adds_mm));
  row("frame_p50", "ms", percentile(o.frame_ms, 0.5));
  row("frame_p95", "ms", percentile(o.frame_ms, 0.95));
  row("frame_mean", "ms", mean(o.frame_ms));
  row("frame_p95_without_search", "ms", percentile(o.tracked_ms, 0.95));
  row("frame_p95_budgeted", "ms", percentile(o.budgeted_ms, 0.95));
  row("frames_over_budget_share", "share", over_share(o.budgeted_ms, budget_ms));
  row("update_cpu_p50_without_search", "ms", percentile(o.cpu_ms, 0.5));
  row("update_cpu_p95_without_search", "ms", percentile(o.cpu_ms, 0.95));
  row("latency_p95", "ms", percentile(o.latency_ms, 0.95));
  row("particles_mean", "particles", mean(o.particles));
  row("frames", "frames", static_cast<double>(o.adds_mm.size()));
}

const char* const kUsage =
    "usage: depthtrack_bench_budget [--backend NAME[,NAME...]] [--particles N[,N...]] [--budget-ms MS[,MS...]]\n"
    "                               [--max-particles N] [--synthetic-frames N] [--objects NAME[,NAME...]] [--seed N]\n"
    "                               [--seeds N]\n"
    "Mean ADD-S against frame time (median, 95th percentile) at 80x60 for fixed particle counts and frame\n"
    "budgets, per YCB-Video object (ycbv-0000, ycbv-0049) and on the synthetic occluded handset; prints CSV rows\n"
    "backend,platform,device,driver,test,metric,unit,value.\n"
    "  --backend     backends to run: reference (one core), cpu (every core), cpu:N, or a device (opencl,\n"
    "                opencl:pocl, cuda, ...; the kernel renderer) (default reference,cpu)\n"
    "  --particles   fixed counts (default 200,50,20)\n"
    "  --budget-ms   frame budgets (default 5,10)\n"
    "  --max-particles N   the most particles a budgeted frame runs (default 200; e.g. 100000 on a GPU)\n"
    "  --synthetic-frames N   frames of the synthetic sequence (default 60)\n"
    "  --objects     YCB-Video objects to track (default every object of both clips)\n"
    "  --seed N      the first seed (default 1)\n"
    "  --seeds N     runs seeds seed .. seed + N - 1 and pools their frames in each row (default 1);\n"
    "                frame_p95_budgeted is over the frames the budget sized (not a search's, not the first\n"
    "                after initialize, which runs a search's budget), frames_over_budget_share their share\n"
    "                over the budget\n";

}  // namespace

int main(int argc, char** argv) {
  try {
    std::vector<std::string> backends = {"reference", "cpu"};
    std::vector<Setting> settings;
    std::vector<int> counts = {200, 50, 20};
    std::vector<double> budgets = {5, 10};
    int synthetic_frames = 60;
    int most_particles = Setting::kDefaultMostParticles;
    uint64_t seed = 1;
    int seeds = 1;
    std::vector<std::string> only_objects;
    bench::ArgReader args(argc, argv);
    for (std::string option = args.next(); !option.empty(); option = args.next()) {
      if (option == "--help") {
        std::fputs(kUsage, stdout);
        return 0;
      } else if (option == "--backend") {
        backends = bench::split(args.value());
      } else if (option == "--particles") {
        counts.clear();
        for (const std::string& n : bench::split(args.value())) counts.push_back(bench::parse_positive(n, option));
      } else if (option == "--budget-ms") {
        budgets.clear();
        for (const std::string& n : bench::split(args.value()))
          budgets.push_back(bench::parse_nonnegative_double(n, option));
      } else if (option == "--max-particles") {
        most_particles = bench::parse_positive(args.value(), option);
      } else if (option == "--synthetic-frames") {
        synthetic_frames = bench::parse_positive(args.value(), option);
      } else if (option == "--objects") {
        only_objects = bench::split(args.value());
      } else if (option == "--seed") {
        seed = static_cast<uint64_t>(bench::parse_positive(args.value(), option));
      } else if (option == "--seeds") {
        seeds = bench::parse_positive(args.value(), option);
      } else {
        throw bench::UsageError{"unknown option '" + option + "'"};
      }
    }
    for (const int n : counts) settings.push_back(Setting{n, 0});
    for (const double ms : budgets)
      if (ms > 0) settings.push_back(Setting{most_particles, ms});

    bench::print_header();
    // The reading path: one depth PNG of the clip decoded, the median of its frames.
    const std::filesystem::path clips[] = {bench::data_dir() / "sequences/ycbv-0000",
                                           bench::data_dir() / "sequences/ycbv-0049"};
    if (std::filesystem::exists(clips[0])) {
      const Sequence s = load_sequence(clips[0], "025_mug");
      std::vector<double> decode;
      for (size_t i = 0; i < s.frames.size(); ++i) {
        const Stopwatch clock;
        const DepthImage d = s.load_depth(i);
        decode.push_back(clock.elapsed_ms());
      }
      bench::print_row(
          {"-", "cpu", bench::cpu_name(), "-", "ycbv-0000_640x480", "png_decode_ms", "ms", bench::median(decode)});
    }
    std::string handset_name;
    const Mesh handset = bench::bench_mesh(handset_name);
    SynthConfig synth;
    synth.frames = synthetic_frames;
    synth.occluder_fraction = 0.3;
    std::vector<SynthFrame> synthetic;
    {
      const Synthesizer scene(handset, synth);
      for (int i = 0; i < synthetic_frames; ++i) synthetic.push_back(scene.frame(i));
    }
    for (const std::string& backend : backends) {
      const Where where = where_of(backend);
      for (const Setting& s : settings) {
        std::vector<TrackerConfig> configs;
        for (int k = 0; k < seeds; ++k) configs.push_back(config_for(backend, s, seed + static_cast<uint64_t>(k)));
        for (const auto& clip : clips) {
          if (!std::filesystem::exists(clip)) continue;
          for (const std::string& object : clip_objects(clip)) {
            if (!only_objects.empty() &&
                std::find(only_objects.begin(), only_objects.end(), object) == only_objects.end())
              continue;
            Outcome o;
            for (const TrackerConfig& config : configs) track_clip_object(clip, object, config, o);
            print(backend, where, clip.filename().string() + "_" + object + "_80x60_" + s.name(), o, s.budget_ms);
          }
        }
        Outcome o;
        for (const TrackerConfig& config : configs) track_synthetic(handset, synthetic, synth, config, o);
        print(backend, where, "synthetic_occluded_" + handset_name + "_80x60_" + s.name(), o, s.budget_ms);
      }
    }
    return 0;
  } catch (const bench::UsageError& e) {
    std::fprintf(stderr, "depthtrack_bench_budget: %s\n%s", e.message.c_str(), kUsage);
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "depthtrack_bench_budget: %s\n", e.what());
    return 1;
  }
}
