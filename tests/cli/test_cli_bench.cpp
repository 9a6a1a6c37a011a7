// depthtrack bench: results.json's rows, cases.csv and the figures from a tiny grid, --max-seconds and
// --no-figures, the bytes formula, median and p95, bench compare's ratios on hand-written files, and bad
// arguments.
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/bench_results.hpp"
#include "cli/step_bytes.hpp"
#include "cli_support.hpp"
#include "device_support.hpp"
#include "filter/device_filter.hpp"

using namespace depthtrack;

namespace {

std::string text_of(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

const nlohmann::json* find_row(const nlohmann::json& rows, const std::string& backend, const std::string& test,
                               const std::string& metric) {
  for (const auto& r : rows)
    if (r["backend"] == backend && r["test"] == test && r["metric"] == metric) return &r;
  return nullptr;
}

}  // namespace

TEST_CASE("median, p95 and the bytes each step moves", "[bench]") {
  CHECK(cli::median_of({3, 1, 2, 4}) == 2.5);
  CHECK(cli::median_of({5, 1, 3}) == 3);
  std::vector<double> twenty;
  for (int i = 20; i >= 1; --i) twenty.push_back(i);
  CHECK(cli::p95_of(twenty) == 19);  // nearest rank: ceil(0.95 * 20) = 19th of 1..20
  CHECK(cli::p95_of({7}) == 7);
  CHECK(std::isnan(cli::median_of({})));
  // 10 particles at 80x60: state 16 floats, atlas and occlusion p a float per pixel, t a 16-bit index.
  const auto b = cli::step_bytes(10, 4800, OcclusionStorage::PerPixelTime, false, 0);
  CHECK(b.propagate == 10 * 2 * 64);
  CHECK(b.render == 10 * 4800 * 4);
  CHECK(b.handoff == 0);
  // weigh: the atlas, the parent's row of p and t, its own row written, parent, log-likelihood and weight.
  CHECK(b.weigh == 10 * (4800 * 4 + 2 * 4800 * 4 + 2 * 4800 * 2 + 12));
  CHECK(b.resample == 10 * (2 * 64 + 12));  // the kinematic state; the rows are weigh's
  CHECK(cli::step_bytes(10, 4800, OcclusionStorage::Off, true, 0).weigh == 10 * (4800 * 4 + 12));
  // Drawn inside weigh: no atlas through memory.
  const auto inside = cli::step_bytes(10, 4800, OcclusionStorage::PerPixelTime, false, 0, true);
  CHECK(inside.render == 0);
  CHECK(inside.weigh == 10 * (2 * 4800 * 4 + 2 * 4800 * 2 + 12));
  // A small cloud's weigh moves the particles too: the motion step's state read and write are its.
  const auto moving = cli::step_bytes(10, 4800, OcclusionStorage::PerPixelTime, false, 0, true, std::nullopt, true);
  CHECK(moving.propagate == 0);
  CHECK(moving.weigh == inside.weigh + 10 * 2 * 64);
  CHECK(cli::step_bytes(10, 4800, OcclusionStorage::Off, true, 0).handoff == 10 * 4800 * 4 * 2);
  // DeviceFilter's buffers: 4 bytes x (4 per pixel: atlas, p twice, t twice in 16 bits; + 2 x 16 state + 6)
  // per particle; 3 per pixel where the atlas stays in work-group memory.
  CHECK(cli::filter_memory_mib(10, 4800, OcclusionStorage::PerPixelTime) == Approx(769520.0 / (1 << 20)));
  CHECK(cli::filter_memory_mib(10, 4800, OcclusionStorage::GlobalTime) == Approx(577520.0 / (1 << 20)));
  CHECK(cli::filter_memory_mib(10, 4800, OcclusionStorage::Off) == Approx(193520.0 / (1 << 20)));
  CHECK(cli::filter_memory_mib(10, 4800, OcclusionStorage::PerPixelTime, 0) == Approx(577520.0 / (1 << 20)));
  // An atlas of 4 tiles drawn in turns: 6 tiles' depths (4800 floats each) fewer than every particle's.
  CHECK(cli::filter_memory_mib(10, 4800, OcclusionStorage::PerPixelTime, 4) ==
        Approx((769520.0 - 6 * 4800 * 4) / (1 << 20)));
  // A state window of 600 pixels: the rows (p and t, read and written; in memory p twice and t twice in
  // 16 bits) shrink to it, the atlas stays the image's.
  CHECK(cli::step_bytes(10, 4800, OcclusionStorage::PerPixelTime, false, 0, false, 600).weigh ==
        10 * (4800 * 4 + 2 * 600 * 4 + 2 * 600 * 2 + 12));
  CHECK(cli::filter_memory_mib(10, 4800, OcclusionStorage::PerPixelTime, std::nullopt, 600) ==
        Approx(10 * 4 * (4800 + 3 * 600 + 38) / double(1 << 20)));
}

TEST_CASE("bench writes results.json with every column and the four figures", "[bench][cli]") {
  const auto dir = test::temp_dir("bench_cli");
  std::string backends = "--backend reference --backend cpu:2";
  const bool device = test::device_available();
  if (device) backends += " --backend " + test::device_selector();
  const auto [status, output] =
      test::run_cli("bench --test-grid --frames 3 " + backends + " --out " + (dir / "out").string(), dir / "log.txt");
  INFO(output);
  REQUIRE(status == 0);
  const auto root = nlohmann::json::parse(text_of(dir / "out/results.json"));
  const auto& rows = root.at("rows");
  REQUIRE(rows.size() > 20);
  for (const auto& r : rows) {
    for (const char* column : {"backend", "platform", "device", "driver", "commit", "test", "metric", "unit"})
      REQUIRE(r.at(column).is_string());
    REQUIRE((r.at("median").is_number() || r.at("median").is_null()));
    REQUIRE((r.at("p95").is_number() || r.at("p95").is_null()));
    REQUIRE(r.at("samples").is_number_integer());
  }
  const std::string mesh = test::shared_data("meshes/dbot/handset.obj") ? "handset" : "builtin";
  const std::string test = "particles_" + mesh + "_80x60_10p_per-pixel-time";
  const auto* frame = find_row(rows, "reference", test, "frame_ms");
  REQUIRE(frame);
  CHECK((*frame)["samples"] == 1);  // 3 frames, 2 of them warm-up
  CHECK((*frame)["median"].get<double>() > 0);
  CHECK((*frame)["median"] == (*frame)["p95"]);
  const auto* render = find_row(rows, "reference", test, "render_bytes");
  REQUIRE(render);
  CHECK((*render)["median"].get<double>() == Approx(10 * 4800 * 4 / 1e6));
  // The latency case runs untimed, as a tracker does; its latency is Tracker::update as the caller waits for
  // it, which holds the filter's frame, so on each frame, and so in the median, at least the frame time.
  const std::string latency_test = "latency_" + mesh + "_80x60_10p_per-pixel-time_untimed";
  for (const char* backend : {"reference", "cpu:2"}) {
    const auto* latency = find_row(rows, backend, latency_test, "latency_ms");
    const auto* latency_frame = find_row(rows, backend, latency_test, "frame_ms");
    REQUIRE(latency);
    REQUIRE(latency_frame);
    CHECK(latency->at("median").get<double>() >= latency_frame->at("median").get<double>());
  }
  const auto* timed_latency = find_row(rows, "reference", test, "latency_ms");
  REQUIRE(timed_latency);
  CHECK(timed_latency->at("median").get<double>() >= frame->at("median").get<double>());
  for (const char* sweep : {"resolution_", "triangles_", "occlusion_", "latency_"}) {
    bool found = false;
    for (const auto& r : rows) found |= r["test"].get<std::string>().rfind(sweep, 0) == 0;
    CHECK(found);
  }
  // The CPU path: its speedup is the reference's frame over its own, and it reports no device memory.
  const auto* cpu_frame = find_row(rows, "cpu:2", test, "frame_ms");
  const auto* cpu_speedup = find_row(rows, "cpu:2", test, "speedup_vs_reference");
  REQUIRE(cpu_frame);
  REQUIRE(cpu_speedup);
  CHECK((*cpu_speedup)["median"].get<double>() ==
        Approx(frame->at("median").get<double>() / cpu_frame->at("median").get<double>()));
  CHECK_FALSE(find_row(rows, "cpu:2", test, "device_memory"));
  if (device) {
    const auto* speedup = find_row(rows, test::device_selector(), test, "speedup_vs_reference");
    const auto* device_frame = find_row(rows, test::device_selector(), test, "frame_ms");
    const auto* memory = find_row(rows, test::device_selector(), test, "device_memory");
    REQUIRE(speedup);
    REQUIRE(device_frame);
    REQUIRE(memory);
    CHECK((*speedup)["median"].get<double>() ==
          Approx(frame->at("median").get<double>() / device_frame->at("median").get<double>()));
    // Without the atlas where the kernel renderer draws inside weigh (the tile fits in work-group memory);
    // the occlusion rows (p twice, t twice in 16 bits: 3 floats a pixel) over the automatic window's pixels.
    const bool inside = renders_inside_weigh(Renderer::Kernel, 4800,
                                             compute::open_device(test::device_selector())->info().local_memory);
    const auto* window = find_row(rows, test::device_selector(), test, "state_window_pixels");
    REQUIRE(window);
    const double kept = window->at("median").get<double>();
    CHECK(kept > 0);
    CHECK(kept < 4800 / 4);  // the handset's window, a fraction of the image
    CHECK(memory->at("median").get<double>() == Approx(10 * 4 * ((inside ? 0 : 4800) + 3 * kept + 38) / (1 << 20)));
  }
  for (const char* figure : {"particles.png", "resolution.png", "triangles.png", "occlusion.png"})
    CHECK(text_of(dir / "out" / figure).rfind("\x89PNG\r\n\x1a\n", 0) == 0);
  // cases.csv, which the figures are drawn from: a row per case run, its frame time results.json's.
  const auto cases = test::lines_of(dir / "out/cases.csv");
  REQUIRE(!cases.empty());
  CHECK(cases[0] == "sweep,backend,mesh,triangles,width,height,particles,occlusion,frame_ms,memory_mib");
  bool found_case = false;
  for (const auto& line : cases) {
    const auto cells = test::cells_of(line);
    if (cells.size() < 9 || cells[0] != "particles" || cells[1] != "reference" || cells[6] != "10") continue;
    found_case = true;
    CHECK(cells[2] == mesh);
    CHECK(cells[7] == "per-pixel-time");
    CHECK(std::stod(cells[8]) == Approx(frame->at("median").get<double>()).epsilon(1e-6));
    CHECK(cells.size() == 9);  // no device memory on the reference: the last cell empty
  }
  CHECK(found_case);

  // A failed run leaves the earlier results.json as it was.
  const std::string before = text_of(dir / "out/results.json");
  const auto [bad, message] =
      test::run_cli("bench --test-grid --backend nosuch --out " + (dir / "out").string(), dir / "bad.txt");
  CHECK(bad != 0);
  CHECK_THAT(message, Catch::Contains("nosuch"));
  CHECK(text_of(dir / "out/results.json") == before);
}

TEST_CASE("bench compare prints each file's column with its ratio to the first", "[bench][cli]") {
  const auto dir = test::temp_dir("bench_compare");
  auto write = [&](const std::string& name, const std::string& backend, double frame, double weigh) {
    std::ofstream(dir / name) << R"({"rows": [)"
                              << R"({"backend": ")" << backend << R"(", "platform": "p", "device": "d", "driver": "1",)"
                              << R"( "commit": "c", "test": "t1", "metric": "frame_ms", "unit": "ms", "median": )"
                              << frame << R"(, "p95": null, "samples": 5},)"
                              << R"({"backend": ")" << backend << R"(", "platform": "p", "device": "d", "driver": "1",)"
                              << R"( "commit": "c", "test": "t1", "metric": "weigh_ms", "unit": "ms", "median": )"
                              << weigh << R"(, "p95": 1, "samples": 5}]})";
  };
  write("a.json", "cuda", 2.0, 1.0);
  write("b.json", "opencl:nvidia", 3.0, 0.25);
  const auto [status, output] =
      test::run_cli("bench compare " + (dir / "a.json").string() + " " + (dir / "b.json").string(), dir / "log.txt");
  INFO(output);
  REQUIRE(status == 0);
  CHECK_THAT(output, Catch::Contains("a.json:cuda") && Catch::Contains("b.json:opencl:nvidia"));
  CHECK_THAT(output, Catch::Contains("(x1.50)"));  // 3.0 / 2.0
  CHECK_THAT(output, Catch::Contains("(x0.25)"));  // 0.25 / 1.0
  // The table itself, without the command: one line per test and metric.
  const auto table = cli::compare_table(
      {{"a.json", cli::read_results(dir / "a.json")}, {"b.json", cli::read_results(dir / "b.json")}});
  CHECK_THAT(table, Catch::Contains("t1 frame_ms") && Catch::Contains("t1 weigh_ms"));
}

TEST_CASE("bench --max-seconds skips the cases that would pass it, each said on stderr", "[bench][cli]") {
  const auto dir = test::temp_dir("bench_max_seconds");
  const std::string run = "bench --test-grid --frames 3 --backend reference --no-figures --out ";
  // A limit no case fits in: every case is skipped, and said so, and nothing is written.
  const auto [none_status, none] =
      test::run_cli(run + (dir / "none").string() + " --max-seconds 0.000001", dir / "none.txt");
  INFO(none);
  CHECK(none_status == 1);
  CHECK_THAT(none, Catch::Contains("bench: reference particles_") && Catch::Contains("(--max-seconds 1e-06)") &&
                       Catch::Contains("no case ran"));
  CHECK_FALSE(std::filesystem::exists(dir / "none/results.json"));
  // A run without a limit, then one with half its time: it stops starting cases that would pass the limit,
  // says so for each, and ends within the limit (give or take the last case's misjudged time and the
  // process' start and exit, well under a second on the test grid).
  const auto begin = std::chrono::steady_clock::now();
  const auto [full_status, full] = test::run_cli(run + (dir / "full").string(), dir / "full.txt");
  const double full_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  REQUIRE(full_status == 0);
  char limit[32];
  std::snprintf(limit, sizeof limit, "%.3f", full_seconds / 2);
  const auto started = std::chrono::steady_clock::now();
  const auto [status, output] =
      test::run_cli(run + (dir / "half").string() + " --max-seconds " + limit, dir / "half.txt");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  INFO(output << "\nfull run " << full_seconds << " s, limit " << limit << " s, limited run " << seconds << " s");
  CHECK((status == 0 || output.find("no case ran") != std::string::npos));
  CHECK_THAT(output, Catch::Contains("skipped to stay within --max-seconds"));
  CHECK(seconds < full_seconds);
  CHECK(seconds < full_seconds / 2 + 1.0);
  if (status != 0) return;  // the meshes' preparation alone took the half
  const auto notes = nlohmann::json::parse(text_of(dir / "half/results.json")).at("notes");
  size_t skipped = 0;
  for (const auto& note : notes) {
    const std::string text = note.get<std::string>();
    if (text.find("--max-seconds") == std::string::npos) continue;
    ++skipped;
    CHECK_THAT(output, Catch::Contains("bench: " + text));  // each on the terminal too
  }
  CHECK(skipped > 0);
}

TEST_CASE("bench --no-figures needs no matplotlib; without it, a missing one fails at once", "[bench][cli]") {
  const auto dir = test::temp_dir("bench_figures");
  const auto [status, output] =
      test::run_cli("bench --test-grid --frames 3 --backend reference --out " + (dir / "out").string(), dir / "log.txt",
                    "DEPTHTRACK_PYTHON=/nonexistent/python3");
  INFO(output);
  CHECK(status == 1);
  CHECK_THAT(output, Catch::Contains("bench (for its figures; --no-figures leaves them out) needs python3 with "
                                     "matplotlib (/nonexistent/python3 was not found)"));
  CHECK_THAT(output, !Catch::Contains("ms per frame"));  // before any case ran
  const auto [plain_status, plain] =
      test::run_cli("bench --test-grid --frames 3 --backend reference --no-figures --out " + (dir / "out").string(),
                    dir / "log.txt", "DEPTHTRACK_PYTHON=/nonexistent/python3");
  INFO(plain);
  REQUIRE(plain_status == 0);
  CHECK(std::filesystem::exists(dir / "out/results.json"));
  CHECK(std::filesystem::exists(dir / "out/cases.csv"));
  CHECK_FALSE(std::filesystem::exists(dir / "out/particles.png"));
  CHECK(plain.find('\r') == std::string::npos);  // no progress bar when stderr is not a terminal
}

TEST_CASE("bench refuses bad arguments and corrupt results with a clear error", "[bench][cli]") {
  const auto dir = test::temp_dir("bench_bad");
  std::ofstream(dir / "file.txt") << "not a folder";
  std::ofstream(dir / "corrupt.json") << "{\"rows\": [ {\"backend\": ";
  std::ofstream(dir / "no_median.json")
      << R"({"rows": [{"backend": "b", "platform": "p", "device": "d", "driver": "1", "commit": "c", "test": "t",)"
      << R"( "metric": "m", "unit": "u", "p95": 1, "samples": 1}]})";
  const std::pair<std::string, std::string> cases[] = {
      {"bench --test-grid --backend nosuch --out " + (dir / "o").string(), "unknown backend 'nosuch'"},
      {"bench --test-grid --backend cpu:0 --out " + (dir / "o").string(),
       "cpu:N takes a thread count N from 1 to 1024"},
      {"bench --test-grid --backend reference", "bench needs --out DIR"},
      {"bench --test-grid --backend reference --out " + (dir / "file.txt/sub").string(),
       "cannot create the output folder"},
      {"bench --test-grid --backend reference --frames 2 --out " + (dir / "o").string(), "--frames must be at least 3"},
      {"bench --renderer vulkan --out " + (dir / "o").string(), "unknown renderer 'vulkan' (choose cpu, gl or kernel)"},
      {"bench compare " + (dir / "corrupt.json").string(), "is not valid JSON"},
      {"bench compare " + (dir / "no_median.json").string(), "row 0 has no 'median'"},
      {"bench compare " + (dir / "absent.json").string(), "absent.json"},
  };
  for (const auto& [arguments, expected] : cases) {
    const auto [status, output] = test::run_cli(arguments, dir / "log.txt");
    INFO(arguments);
    CHECK(status != 0);
    CHECK_THAT(output, Catch::Contains(expected));
  }
}

TEST_CASE("a bench whose figures fail leaves the earlier results, cases and figures as they were", "[bench][cli]") {
  const auto dir = test::temp_dir("bench_failed_figures");
  const auto out = dir / "out";
  std::filesystem::create_directories(out);
  for (const char* name : {"results.json", "cases.csv", "particles.png"}) std::ofstream(out / name) << "earlier\n";
  // An interpreter that passes the matplotlib check, then fails to draw: the run fails after its cases.
  const auto python = dir / "failing-python";
  std::ofstream(python) << "#!/bin/sh\n[ \"$1\" = -c ] && exit 0\nexit 3\n";
  std::filesystem::permissions(python, std::filesystem::perms::owner_all);
  const auto [status, output] = test::run_cli("bench --test-grid --frames 3 --backend reference --out " + out.string(),
                                              dir / "log.txt", "DEPTHTRACK_PYTHON=" + python.string());
  INFO(output);
  CHECK(status == 1);
  CHECK_THAT(output, Catch::Contains("drawing the figure failed"));
  for (const char* name : {"results.json", "cases.csv", "particles.png"}) CHECK(text_of(out / name) == "earlier\n");
  for (const auto& entry : std::filesystem::directory_iterator(out))
    CHECK(entry.path().filename().string().find(".partial") == std::string::npos);
}
