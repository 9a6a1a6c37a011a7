// The small frictions of a first try, each with its exit code and message: backend names, options
// that do nothing, meshes in the wrong unit, progress, --version, the benchmarks' command lines, the
// configuration's keys described, one default initial spread.
#include <catch2/catch.hpp>
#include <depthtrack/tracker.hpp>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <regex>
#include <sstream>

#include "cli_support.hpp"

using namespace depthtrack;

namespace {
std::string track_args(const std::filesystem::path& dir, const std::string& mesh = "object.obj") {
  return "track --mesh " + (dir / mesh).string() + " --sequence " + (dir / "seq").string() + " --out " +
         (dir / "out.csv").string() + " --resolution 80x60 --particles 50 --init-from-gt";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}
}  // namespace

TEST_CASE("an unknown backend is named once, without a stray quote", "[cli][errors]") {
  const auto dir = test::write_cli_sequence("cli_rough_backend", 2);
  const auto [status, output] = test::run_cli(track_args(dir) + " --backend quantum", dir / "log.txt");
  INFO(output);
  CHECK(status == 1);
  CHECK(contains(output, "unknown backend 'quantum'; available: reference, cpu, cpu:<threads>, opencl"));
  CHECK(!contains(output, "''"));
}

TEST_CASE("track --renderer with the reference backend warns that it has no effect", "[cli]") {
  const auto dir = test::write_cli_sequence("cli_rough_renderer", 2);
  const auto [status, output] = test::run_cli(track_args(dir) + " --backend reference --renderer gl", dir / "log.txt");
  INFO(output);
  CHECK(status == 0);
  CHECK(contains(output, "warning: --renderer gl has no effect with the reference backend"));
  // Without --renderer nothing is said.
  const auto [plain_status, plain] = test::run_cli(track_args(dir) + " --backend reference", dir / "log.txt");
  CHECK(plain_status == 0);
  CHECK(!contains(plain, "--renderer"));
}

TEST_CASE("a mesh spanning more than 5 m or less than 1 mm gets a warning naming --unit-scale", "[cli]") {
  const auto dir = test::write_cli_sequence("cli_rough_scale", 2);
  test::write_obj(dir / "millimetres.obj", builtin_demo_mesh(), 1000.0);  // 16 cm object written in mm
  test::write_obj(dir / "tiny.obj", builtin_demo_mesh(), 0.001);
  const auto [mm_status, mm] = test::run_cli(track_args(dir, "millimetres.obj"), dir / "log.txt");
  INFO(mm);
  // The warning comes first; then the start, 1000x too far from the mesh's centre, is refused.
  CHECK(mm_status == 1);
  CHECK(contains(mm, "warning: mesh '" + (dir / "millimetres.obj").string() + "' spans 160 m"));
  CHECK(contains(mm, "behind or too close to the camera"));
  CHECK(contains(mm, "check --unit-scale"));
  // The right factor silences it.
  const auto [fixed_status, fixed] =
      test::run_cli(track_args(dir, "millimetres.obj") + " --unit-scale 0.001", dir / "log.txt");
  CHECK(fixed_status == 0);
  CHECK(!contains(fixed, "warning"));
  const auto [tiny_status, tiny] = test::run_cli(track_args(dir, "tiny.obj"), dir / "log.txt");
  CHECK(tiny_status == 0);
  CHECK(contains(tiny, "spans 0.00016 m"));
  // synth warns the same way.
  const auto [synth_status, synth] =
      test::run_cli("synth --mesh " + (dir / "millimetres.obj").string() + " --out " + (dir / "synth").string() +
                        " --frames 1 --resolution 80x60 --background 0",
                    dir / "log.txt");
  CHECK(contains(synth, "check --unit-scale"));
  (void)synth_status;  // the 160 m object fills the view; only the warning matters here
}

TEST_CASE("track draws a progress bar when stderr is a terminal", "[cli]") {
  // util-linux's script gives the command a terminal; a machine without it, or without ptys, skips.
  if (std::system("script -qec true /dev/null > /dev/null 2>&1") != 0) {
    std::cout << "SKIPPED: 'script' cannot give the command a terminal here (not installed, or no pty)\n";
    return;
  }
  const auto dir = test::write_cli_sequence("cli_rough_progress", 3);
  const std::string command = "script -qec '" + std::string(DEPTHTRACK_CLI) + " " + track_args(dir) + "' /dev/null > " +
                              (dir / "log.txt").string() + " 2>&1";
  const int status = std::system(command.c_str());
  const auto lines = test::lines_of(dir / "log.txt");
  std::string output;
  for (const auto& l : lines) output += l + "\n";
  INFO(output);
  CHECK(WEXITSTATUS(status) == 0);
  CHECK(contains(output, "tracking ["));
  CHECK(contains(output, "] 3/3 err "));
  // Redirected to a file, no bar (no carriage returns in logs).
  const auto [plain_status, plain] = test::run_cli(track_args(dir), dir / "plain.txt");
  CHECK(plain_status == 0);
  CHECK(!contains(plain, "tracking ["));
}

TEST_CASE("depthtrack --version prints the version and exits 0", "[cli]") {
  const auto dir = test::temp_dir("cli_rough_version");
  const auto [status, output] = test::run_cli("--version", dir / "log.txt");
  CHECK(status == 0);
  CHECK(std::regex_match(output, std::regex("depthtrack [0-9]+\\.[0-9]+\\.[0-9]+\n")));
}

TEST_CASE("the benchmarks answer --help and refuse malformed numbers", "[cli][bench]") {
  const std::string bench_dir = DEPTHTRACK_BENCH_DIR;
  if (bench_dir.empty()) {
    std::cout << "SKIPPED: the benchmarks are not built (DEPTHTRACK_BUILD_BENCH=OFF)\n";
    return;
  }
  const auto dir = test::temp_dir("cli_rough_bench");
  auto run = [&](const std::string& program, const std::string& arguments) {
    const std::string command =
        bench_dir + "/" + program + " " + arguments + " > " + (dir / "log.txt").string() + " 2>&1";
    const int status = std::system(command.c_str());
    std::string output;
    for (const auto& l : test::lines_of(dir / "log.txt")) output += l + "\n";
    return std::pair{WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
  };
  // depthtrack_bench_atlas is built only with the GL atlas (DEPTHTRACK_WITH_GL).
  auto built = [](const std::string& program) {
#ifndef DEPTHTRACK_WITH_GL
    if (program == "depthtrack_bench_atlas") return false;
#endif
    return !program.empty();
  };
  for (const char* program : {"depthtrack_bench", "depthtrack_bench_atlas", "depthtrack_bench_soak",
                              "depthtrack_bench_startup", "depthtrack_bench_error_axes", "depthtrack_bench_budget"}) {
    if (!built(program)) continue;
    const auto [status, help] = run(program, "--help");
    INFO(program << "\n" << help);
    CHECK(status == 0);
    CHECK(contains(help, std::string("usage: ") + program));
    CHECK(contains(help, "--particles"));
  }
  struct Case {
    const char *program, *arguments, *expected;
  };
  const Case cases[] = {
      {"depthtrack_bench", "--frames 12x", "--frames: '12x' is not a positive integer"},
      {"depthtrack_bench", "--particles 200,abc", "--particles: 'abc' is not a positive integer"},
      {"depthtrack_bench", "--particles -5", "--particles: '-5' is not a positive integer"},
      {"depthtrack_bench", "--resolution 80x", "--resolution: '' is not a positive integer"},
      {"depthtrack_bench", "--resolution 80by60", "is not of the form WxH"},
      {"depthtrack_bench", "--frames", "--frames needs a value"},
      {"depthtrack_bench", "--fast", "unknown option '--fast'"},
      {"depthtrack_bench", "--pace -1", "--pace: '-1' is not a number >= 0"},
      {"depthtrack_bench", "--refine-layout wide",
       "unknown refinement layout 'wide' (choose auto, one-group, spread or one-launch)"},
      {"depthtrack_bench_atlas", "--repeats 0", "--repeats: '0' is not a positive integer"},
      {"depthtrack_bench_atlas", "--particles 1e3", "--particles: '1e3' is not a positive integer"},
      {"depthtrack_bench_soak", "--frames 0", "--frames: '0' is not a positive integer"},
      {"depthtrack_bench_soak", "--every", "--every needs a value"},
      {"depthtrack_bench_startup", "--frames 0", "--frames: '0' is not a positive integer"},
      {"depthtrack_bench_error_axes", "--refine maybe", "--refine takes on or off, not 'maybe'"},
      {"depthtrack_bench_error_axes", "--sigma-angular -0.1", "--sigma-angular: '-0.1' is not a number >= 0"},
      {"depthtrack_bench_error_axes", "--fine-refit 320", "is not of the form WxH"},
      {"depthtrack_bench_budget", "--budget-ms -1", "--budget-ms: '-1' is not a number >= 0"},
      {"depthtrack_bench_budget", "--particles 0", "--particles: '0' is not a positive integer"},
      {"depthtrack_bench_budget", "--max-particles 0", "--max-particles: '0' is not a positive integer"},
  };
  for (const Case& c : cases) {
    if (!built(c.program)) continue;
    const auto [status, output] = run(c.program, c.arguments);
    INFO(c.program << " " << c.arguments << "\n" << output);
    CHECK(status == 2);
    CHECK(contains(output, c.expected));
    CHECK(contains(output, std::string("usage: ") + c.program));
  }
}

TEST_CASE("bench draws its progress bar when stderr is a terminal", "[cli][bench]") {
  if (std::system("script -qec true /dev/null > /dev/null 2>&1") != 0) {
    std::cout << "SKIPPED: 'script' cannot give the command a terminal here (not installed, or no pty)\n";
    return;
  }
  const auto dir = test::temp_dir("cli_rough_bench_progress");
  const std::string command = "script -qec '" + std::string(DEPTHTRACK_CLI) +
                              " bench --test-grid --frames 3 --backend reference --no-figures --out " +
                              (dir / "out").string() + "' /dev/null > " + (dir / "log.txt").string() + " 2>&1";
  const int status = std::system(command.c_str());
  const std::string output = test::text_of(dir / "log.txt");
  INFO(output);
  CHECK(WEXITSTATUS(status) == 0);
  CHECK(std::regex_search(output, std::regex("bench \\[#* *\\] [0-9]+/[0-9]+ reference")));
  CHECK(contains(output, "ms per frame"));
}

TEST_CASE("config --describe gives every key of --dump with its value, unit and meaning", "[cli][config]") {
  const auto dir = test::temp_dir("cli_rough_describe");
  const auto [dump_status, dump] = test::run_cli("config --dump", dir / "dump.txt");
  REQUIRE(dump_status == 0);
  const auto [status, output] = test::run_cli("config --describe", dir / "describe.txt");
  INFO(output);
  REQUIRE(status == 0);
  std::map<std::string, std::string> lines;  // key -> the rest of its line
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) {
    const size_t end = line.find(' ');
    CHECK(lines.emplace(line.substr(0, end), line.substr(end)).second);  // each key once
  }
  CHECK(contains(lines.at("key"), "default"));
  // Every leaf of the JSON --dump prints has a line holding its value.
  size_t leaves = 0;
  std::function<void(const nlohmann::json&, const std::string&)> walk = [&](const nlohmann::json& j,
                                                                            const std::string& prefix) {
    for (const auto& [key, value] : j.items()) {
      if (value.is_object()) {
        walk(value, prefix + key + ".");
        continue;
      }
      ++leaves;
      const std::string path = prefix + key;
      std::string shown(1, ' ');  // the value between the columns' spaces
      shown.append(value.dump()).append(1, ' ');
      INFO(path);
      REQUIRE(lines.count(path) == 1);
      CHECK(contains(lines.at(path), shown));
    }
  };
  walk(nlohmann::json::parse(dump), "");
  CHECK(leaves > 40);
  CHECK(std::regex_search(lines.at("observation.sigma_constant"), std::regex("^ +0\\.003 +m +depth noise")));
  CHECK(std::regex_search(lines.at("recovery.budget_ms"), std::regex("^ +500\\.0 +ms +wall-clock")));
  CHECK(std::regex_search(lines.at("max_time_step"), std::regex("^ +0\\.2 +s +the longest gap")));
  // With --config, that file's values.
  std::ofstream(dir / "c.json") << R"({"particles": 40})";
  const auto [file_status, file] =
      test::run_cli("config --describe --config " + (dir / "c.json").string(), dir / "c.txt");
  REQUIRE(file_status == 0);
  CHECK(std::regex_search(file, std::regex("\nparticles +40 +particles +number of particles[ (]")));
  CHECK(file.rfind("key", 0) == 0);
  CHECK(contains(file.substr(0, file.find('\n')), "value"));
  const auto [none_status, none] = test::run_cli("config", dir / "none.txt");
  CHECK(none_status == 1);
  CHECK(contains(none, "config: give one of --dump (JSON) and --describe (a table)"));
}

TEST_CASE("the default initial spread is one: 1 cm and 5 degrees in the library, track and eval", "[cli]") {
  CHECK(InitialSpread{}.metres == 0.01);
  CHECK(InitialSpread{}.radians == Approx(5 * std::numbers::pi / 180));
  const auto dir = test::temp_dir("cli_rough_spread");
  for (const char* command : {"track", "eval"}) {
    const auto [status, help] = test::run_cli(std::string(command) + " --help", dir / "help.txt");
    INFO(help);
    CHECK(status == 0);
    CHECK(std::regex_search(help, std::regex("--init-spread TEXT=0\\.01 5 ")));
  }
}
