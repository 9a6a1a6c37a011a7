// depthtrack plot: the figure depthtrack/plots.py draws from a track CSV (its size follows its panels),
// several objects, the timeline, bad CSVs and a missing matplotlib named.
#include <catch2/catch.hpp>
#include <fstream>

#include "cli_support.hpp"

using namespace depthtrack;

namespace {

// Width and height from a PNG's header; (0, 0) when the file is not a PNG.
std::pair<int, int> png_size(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char header[24] = {};
  in.read(reinterpret_cast<char*>(header), sizeof header);
  if (!in || header[1] != 'P' || header[2] != 'N' || header[3] != 'G') return {0, 0};
  auto big_endian = [&](int at) {
    return (header[at] << 24) | (header[at + 1] << 16) | (header[at + 2] << 8) | header[at + 3];
  };
  return {big_endian(16), big_endian(20)};
}

bool no_matplotlib(const std::string& output) {
  if (output.find("needs python3 with matplotlib") == std::string::npos) return false;
  std::printf("SKIPPED: no python3 with matplotlib here\n");
  return true;
}

}  // namespace

TEST_CASE("depthtrack plot draws a panel per column present", "[viz][cli]") {
  const auto dir = test::temp_dir("plot_cli");
  {
    std::ofstream csv(dir / "run.csv");
    csv << "frame,timestamp,tx,ty,tz,qw,qx,qy,qz,ess,err_t_mm,err_r_deg,adds_mm,confidence,status,latency_ms\n";
    for (int i = 0; i < 5; ++i)
      csv << "00000" << i << "," << i / 30.0 << ",0,0,0.8,1,0,0,0," << 10 + i << "," << i << ",0.5," << 0.8 * i
          << ",0.9,tracking," << (i == 2 ? "" : "4.5") << "\n";
  }
  const auto [status, output] =
      test::run_cli("plot " + (dir / "run.csv").string() + " --out " + (dir / "run.png").string(), dir / "log.txt");
  if (no_matplotlib(output)) return;
  INFO(output);
  REQUIRE(status == 0);
  CHECK(output.find("wrote " + (dir / "run.png").string() + ": 5 panels, 5 frames") != std::string::npos);
  // 9.6 x (0.8 + 2.2 per panel) inches at 100 dpi.
  CHECK(png_size(dir / "run.png") == std::pair{960, 80 + 5 * 220});
  CHECK_FALSE(std::filesystem::exists(dir / "run.png.partial"));

  // A CSV without ground truth: ESS, confidence and latency.
  {
    std::ofstream csv(dir / "plain.csv");
    csv << "frame,timestamp,tx,ty,tz,qw,qx,qy,qz,ess\n000000,0,0,0,1,1,0,0,0,3\n000001,0.1,0,0,1,1,0,0,0,4\n";
  }
  const auto [plain_status, plain] =
      test::run_cli("plot " + (dir / "plain.csv").string() + " --out " + (dir / "plain.png").string(), dir / "log.txt");
  CHECK(plain_status == 0);
  CHECK(plain.find("1 panel, 2 frames") != std::string::npos);
  CHECK(png_size(dir / "plain.png") == std::pair{960, 80 + 220});
}

TEST_CASE("depthtrack plot draws several objects as lines of their own, and the timeline", "[viz][cli]") {
  const auto dir = test::temp_dir("plot_objects");
  {
    std::ofstream csv(dir / "two.csv");
    csv << "object,frame,timestamp,tx,ty,tz,qw,qx,qy,qz,ess,err_t_mm,err_r_deg,adds_mm,latency_ms,confidence,status\n";
    for (int i = 0; i < 6; ++i)
      for (const char* object : {"mug", "box"})
        csv << object << ",00000" << i << "," << i / 30.0 << ",0,0,0.8,1,0,0,0,40," << 2 + i << ",1," << 1 + i << ",5,"
            << (i == 3 ? 0.2 : 0.9) << "," << (i == 3 ? "lost" : "tracking") << "\n";
  }
  const auto [status, output] =
      test::run_cli("plot " + (dir / "two.csv").string() + " --out " + (dir / "two.png").string(), dir / "log.txt");
  if (no_matplotlib(output)) return;
  INFO(output);
  REQUIRE(status == 0);
  CHECK(output.find("5 panels, 6 frames, 2 objects") != std::string::npos);
  const auto [timeline_status, timeline] = test::run_cli(
      "plot --timeline " + (dir / "two.csv").string() + " --out " + (dir / "t.png").string(), dir / "log.txt");
  INFO(timeline);
  REQUIRE(timeline_status == 0);
  CHECK(timeline.find("error and confidence timeline, 6 frames, 2 lost, 2 objects") != std::string::npos);
  CHECK(png_size(dir / "t.png") == std::pair{960, 90 + 2 * 260});  // a row of 2.6 inches per object
}

TEST_CASE("depthtrack plot refuses files that are not a run's CSV", "[viz][cli][errors]") {
  const auto dir = test::temp_dir("plot_errors");
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  };
  struct Case {
    std::string file, expected;
  };
  const Case cases[] = {
      {(dir / "missing.csv").string(), "cannot open the run CSV"},
      {write("empty.csv", ""), "is empty: expected a header line"},
      {write("header.csv", "frame,ess\n"), "has a header but no rows"},
      {write("short.csv", "frame,ess\n0,1\n1\n"), "line 3 has 1 cells; the header has 2"},
      {write("word.csv", "frame,ess\n0,1\n1,lots\n"), "line 3: column 'ess' holds 'lots', not a number"},
      {write("other.csv", "a,b\n1,2\n"), "has none of the columns plot shows"},
  };
  for (const Case& c : cases) {
    const auto [status, output] =
        test::run_cli("plot " + c.file + " --out " + (dir / "x.png").string(), dir / "log.txt");
    if (no_matplotlib(output)) return;
    INFO(c.file << "\n" << output);
    CHECK(status == 1);
    CHECK(output.rfind("depthtrack: error: ", 0) == 0);  // plots.py's message as depthtrack's own
    CHECK(output.find(c.expected) != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir / "x.png"));
  }
}

TEST_CASE("depthtrack plot names the missing python3 or matplotlib", "[viz][cli][errors]") {
  const auto dir = test::temp_dir("plot_no_python");
  std::ofstream(dir / "run.csv") << "frame,ess\n0,1\n";
  const auto [status, output] =
      test::run_cli("plot " + (dir / "run.csv").string() + " --out " + (dir / "x.png").string(), dir / "log.txt",
                    "DEPTHTRACK_PYTHON=/nonexistent/python3");
  INFO(output);
  CHECK(status == 1);
  CHECK(output.find("plot needs python3 with matplotlib (/nonexistent/python3 was not found): install it (Debian: "
                    "apt install python3-matplotlib)") != std::string::npos);
#ifdef DEPTHTRACK_TEST_PYTHON
  // An interpreter whose matplotlib cannot be imported.
  std::filesystem::create_directories(dir / "fake/matplotlib");
  std::ofstream(dir / "fake/matplotlib/__init__.py") << "raise ImportError('not here')\n";
  const auto [fake_status, fake] = test::run_cli(
      "plot " + (dir / "run.csv").string() + " --out " + (dir / "x.png").string(), dir / "log.txt",
      "DEPTHTRACK_PYTHON=" + std::string(DEPTHTRACK_TEST_PYTHON) + " PYTHONPATH=" + (dir / "fake").string());
  INFO(fake);
  CHECK(fake_status == 1);
  CHECK(fake.find(std::string(DEPTHTRACK_TEST_PYTHON) + " lacks matplotlib") != std::string::npos);
#endif
}
