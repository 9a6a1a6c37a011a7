// depthtrack bench: the thesis' evaluation on the devices present, as results.json and PNG figures;
// depthtrack bench compare: the cross-vendor table of several results.json files.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <depthtrack/error.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>

#include "bench_commit.h"  // DEPTHTRACK_COMMIT, generated at build time
#include "bench_rows.hpp"
#include "cli/bench_figures.hpp"
#include "cli/bench_results.hpp"
#include "cli/bench_suite.hpp"
#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "cli/python_plots.hpp"
#include "cli/staged_outputs.hpp"
#include "compute/queue.hpp"

namespace depthtrack::cli {

namespace fs = std::filesystem;

namespace {

struct BenchArgs {
  std::vector<std::string> backends;
  std::string renderer = "kernel", out;
  bool quick = false, test_grid = false, no_figures = false;
  int frames = 0;
  double max_seconds = 0;
  CLI::Option *frames_option = nullptr, *max_seconds_option = nullptr;  // given or not
  std::vector<std::string> compare_files;
};

// Creates dir and checks a file can be written there before any case runs.
void check_writable(const fs::path& dir) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) throw InputError("cannot create the output folder '" + dir.string() + "': " + error.message());
  const fs::path probe = dir / ".depthtrack-bench-probe";
  if (!std::ofstream(probe)) throw InputError("cannot write into the output folder '" + dir.string() + "'");
  fs::remove(probe, error);
}

// The handset (or the built-in mesh when the data is absent) first, then the YCB mug and the bunny.
std::vector<BenchMesh> load_meshes(int frames, std::vector<std::string>& notes) {
  const fs::path data = bench::data_dir();
  std::vector<BenchMesh> meshes;
  const std::pair<const char*, const char*> wanted[] = {{"handset", "meshes/dbot/handset.obj"},
                                                        {"ycb-mug", "meshes/ycb/025_mug.obj"},
                                                        {"bunny", "meshes/stanford/bunny-69451.obj"}};
  for (const auto& [name, relative] : wanted) {
    const fs::path path = data / relative;
    if (fs::exists(path)) {
      const ProgressWait wait(std::string("bench: preparing ") + name + " and its sequence");
      meshes.push_back(make_bench_mesh(name, Mesh::load(path), frames));
      continue;
    }
    notes.push_back(path.string() + " is absent (third-party data, DEPTHTRACK_DATA_DIR): no " + name + " cases");
    std::fprintf(stderr, "bench: note: %s\n", notes.back().c_str());
    if (meshes.empty() && std::string(name) == "handset")
      meshes.push_back(make_bench_mesh("builtin", builtin_demo_mesh(), frames));
  }
  return meshes;
}

// The time a case should take on a target: the slowest rate (seconds per particle per pixel-or-triangle)
// of the cases run on it so far, times the case's work; 0 before any ran.
struct CaseClock {
  std::map<std::string, double> rate;
  static double work(const BenchCase& c) {
    return static_cast<double>(c.particles) *
           (static_cast<double>(c.width) * c.height + static_cast<double>(c.mesh->mesh.triangles.size()));
  }
  double expected(const std::string& backend, const BenchCase& c) const {
    const auto it = rate.find(backend);
    return it == rate.end() ? 0 : it->second * work(c);
  }
  void ran(const std::string& backend, const BenchCase& c, double seconds) {
    double& r = rate[backend];
    r = std::max(r, seconds / work(c));
  }
};

void run_bench(const BenchArgs& a) {
  const auto start = std::chrono::steady_clock::now();  // --max-seconds counts from here
  const auto since_start = [&start] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  if (a.out.empty()) throw InputError("bench needs --out DIR (where results.json and the figures go)");
  renderer_from_string(a.renderer);  // InputError naming the choices
  BenchGrid grid = a.test_grid ? test_grid() : a.quick ? quick_grid() : full_grid();
  if (a.frames_option->count() > 0) {
    if (a.frames < 3)
      throw InputError("--frames must be at least 3 (two warm-up frames are not timed), got " +
                       std::to_string(a.frames) + "; leave it out for the grid's");
    grid.frames = a.frames;
  }
  // Left out, there is no limit; given, it must be one.
  if (a.max_seconds_option->count() > 0 && !(std::isfinite(a.max_seconds) && a.max_seconds > 0))
    throw InputError("--max-seconds " + std::to_string(a.max_seconds) +
                     " is not a time limit: give a positive number of seconds, or leave it out for none");
  check_writable(a.out);
  // The figures need python3 with matplotlib: checked before any case runs.
  std::optional<PlotRunner> plots;
  if (!a.no_figures) plots = find_plot_runner("bench (for its figures; --no-figures leaves them out)");
  // Every backend is opened before any case runs, so a wrong name fails at once.
  std::vector<std::string> backends = a.backends;
  if (backends.empty()) {
    backends.push_back("reference");
    backends.push_back("cpu");  // the reference on every hardware thread: the CPU path a user would pick
    for (const auto& d : compute::list_devices()) backends.push_back(d.selector);
  }
  std::vector<BenchTarget> targets;
  for (const std::string& b : backends) targets.push_back(describe_target(b));
  std::stable_partition(targets.begin(), targets.end(), [](const BenchTarget& t) { return t.backend == "reference"; });

  BenchResults results;
  const std::vector<BenchMesh> meshes = load_meshes(grid.frames, results.notes);
  const std::vector<BenchCase> cases = grid_cases(grid, meshes);
  std::vector<CaseResult> outcomes;
  std::map<std::string, double> reference_ms;
  CaseClock clock;
  ProgressBar bar("bench", static_cast<int>(targets.size() * cases.size()));
  int done = 0, skipped_for_time = 0;
  char limit[32];
  std::snprintf(limit, sizeof limit, "%g", a.max_seconds);
  for (const BenchTarget& target : targets) {
    for (const BenchCase& c : cases) {
      bar.update(done++, target.backend);
      const std::string what = target.backend + " " + c.test();
      const double elapsed = since_start(), expected = clock.expected(target.backend, c);
      std::string skip;
      if (a.max_seconds > 0 && elapsed + expected > a.max_seconds) {
        char reason[160];
        if (expected > 0)
          std::snprintf(reason, sizeof reason,
                        "skipped: %.2f s passed and it would take about %.2f s (--max-seconds %s)", elapsed, expected,
                        limit);
        else
          std::snprintf(reason, sizeof reason, "skipped: %.2f s passed (--max-seconds %s)", elapsed, limit);
        skip = reason;
        ++skipped_for_time;
      } else if (target.cpu && static_cast<double>(c.particles) * c.width * c.height > grid.cpu_max_work) {
        skip = "skipped on a CPU: particles x pixels beyond this grid's CPU limit";
      }
      if (!skip.empty()) {
        results.notes.push_back(what + ": " + skip);
        bar.note("bench: " + results.notes.back());
        continue;
      }
      const auto ref = reference_ms.find(c.test());
      try {
        const double before = since_start();
        const CaseResult r = run_case(c, target, a.renderer, grid.frames, DEPTHTRACK_COMMIT,
                                      ref == reference_ms.end() ? NAN : ref->second, results.rows);
        clock.ran(target.backend, c, since_start() - before);
        if (target.backend == "reference") reference_ms[c.test()] = r.frame_ms;
        outcomes.push_back(r);
        char line[64];
        std::snprintf(line, sizeof line, ": %.3f ms per frame", r.frame_ms);
        bar.note("bench: " + what + line);
      } catch (const Error& e) {
        const std::string reason = e.what();
        results.notes.push_back(what + ": failed: " + reason.substr(0, reason.find('\n')));
        bar.note("bench: " + results.notes.back());
      }
    }
  }
  bar.update(done);
  bar.finish();
  if (skipped_for_time > 0)
    std::fprintf(stderr,
                 "bench: %d case%s skipped to stay within --max-seconds %s (the notes in results.json list them)\n",
                 skipped_for_time, skipped_for_time == 1 ? "" : "s", limit);
  if (results.rows.empty()) throw Error("no case ran (see the notes above); " + a.out + "/results.json not written");
  // results.json and the figures replace an earlier run's together, once all are written.
  StagedOutputs outputs;
  const fs::path json = fs::path(a.out) / "results.json";
  write_results(results, outputs.add("--out", json));
  const fs::path cases_csv = fs::path(a.out) / "cases.csv";
  const fs::path cases_partial = outputs.add("--out", cases_csv);
  write_bench_cases(outcomes, cases_partial);
  std::vector<fs::path> figures;
  if (plots) {
    std::vector<std::string> arguments{"bench", cases_partial.string()};
    for (const std::string& sweep : figure_sweeps(outcomes)) {
      figures.push_back(fs::path(a.out) / (sweep + ".png"));
      arguments.push_back(sweep + "=" + outputs.add("--out", figures.back()).string());
    }
    const ProgressWait wait("bench: drawing the figures");
    if (!figures.empty()) run_plots(*plots, arguments);
  }
  outputs.commit();
  std::printf("%s", compare_table({{json.string(), results}}).c_str());
  std::printf("wrote %s (%zu rows, %zu notes), %s", json.c_str(), results.rows.size(), results.notes.size(),
              cases_csv.filename().c_str());
  for (const auto& f : figures) std::printf(", %s", f.filename().c_str());
  std::printf("\n");
}

void run_compare(const std::vector<std::string>& files) {
  std::vector<std::pair<std::string, BenchResults>> loaded;
  for (const std::string& f : files) loaded.emplace_back(f, read_results(f));
  std::printf("%s", compare_table(loaded).c_str());
}

}  // namespace

void add_bench_command(CLI::App& app) {
  auto args = std::make_shared<BenchArgs>();
  CLI::App* c = app.add_subcommand(
      "bench",
      "Run the thesis' evaluation (frame time vs particles, resolution, triangles; occlusion modes' time and "
      "memory; per-step split with bytes moved and GB/s; speedup over the reference) on the devices present; "
      "write DIR/results.json, DIR/cases.csv (a row per case) and PNG figures (python3 with matplotlib draws them)");
  c->add_option("--backend", args->backends,
                "Backend to measure, repeatable: reference, cpu, cpu:N or a device (default: the reference, cpu and "
                "every device `depthtrack info` lists)");
  c->add_option("--renderer", args->renderer, "Atlas renderer of device backends: kernel (default), gl, cpu");
  c->add_option("--out", args->out, "Folder for results.json, cases.csv and the figures (created)");
  c->add_flag("--quick", args->quick, "The small grid: a few minutes on a 2-core CPU (PoCL and the reference)");
  c->add_flag("--test-grid", args->test_grid, "The tiniest grid, for the test suite (seconds)");
  args->frames_option =
      c->add_option("--frames", args->frames, "Frames per case, the first two not timed (default: the grid's)");
  args->max_seconds_option =
      c->add_option("--max-seconds", args->max_seconds,
                    "Time limit of the run: a case is skipped (and said so on stderr and in the notes) when the "
                    "time passed plus its expected time (from the cases run before it on the same backend) "
                    "would exceed it; the figures are drawn after");
  c->add_flag("--no-figures", args->no_figures,
              "Write results.json and cases.csv but no PNG figures (which need python3 with matplotlib)");
  CLI::App* compare =
      c->add_subcommand("compare", "Print the cross-vendor table of results.json files, ratios to the first");
  compare->add_option("files", args->compare_files, "results.json files")->required()->check(CLI::ExistingFile);
  compare->callback([args] { run_compare(args->compare_files); });
  c->callback([args, compare] {
    if (!compare->parsed()) run_bench(*args);
  });
}

}  // namespace depthtrack::cli
