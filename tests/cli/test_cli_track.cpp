// The depthtrack track contract: options, CSV columns, exit codes and messages.
#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"

using namespace depthtrack;

TEST_CASE("track writes one CSV row per frame with the contract's columns", "[cli]") {
  const auto dir = test::write_cli_sequence("cli_track");
  const auto [status, output] =
      test::run_cli("track --mesh " + (dir / "object.obj").string() + " --sequence " + (dir / "seq").string() +
                        " --out " + (dir / "out.csv").string() +
                        " --resolution 80x60 --particles 100 --init-from-gt --occlusion global-time --seed 4",
                    dir / "log.txt");
  INFO(output);
  REQUIRE(status == 0);
  const auto lines = test::lines_of(dir / "out.csv");
  REQUIRE(lines.size() == 7);
  CHECK(lines[0] == "frame,timestamp,tx,ty,tz,qw,qx,qy,qz,ess,err_t_mm,err_r_deg,adds_mm,latency_ms,confidence,status");
  // Row 3: frame name, timestamp 2/30 s, and a translation error under 1 cm.
  const auto cells = test::cells_of(lines[3]);
  REQUIRE(cells.size() == 16);
  CHECK(cells[0] == "000002");
  CHECK(std::stod(cells[14]) > 0.5);  // confidence: the object is in view and tracked
  CHECK(cells[15] == "tracking");
  CHECK(std::stod(cells[1]) == Approx(2.0 / 30));
  CHECK(std::stod(cells[4]) == Approx(0.8).margin(0.15));  // tz near the trajectory's 0.8 m
  CHECK(std::stod(cells[10]) < 10.0);
  // Latency: a frame of 100 particles at 80x60 takes some time, and far less than a second.
  CHECK(std::stod(cells[13]) > 0.0);
  CHECK(std::stod(cells[13]) < 1000.0);
  CHECK(output.find("frames per second") != std::string::npos);
}

TEST_CASE("track --init starts from a given pose, and its CSV then has no error columns", "[cli]") {
  const auto dir = test::write_cli_sequence("cli_track_init", 2);
  const auto [status, output] =
      test::run_cli("track --mesh " + (dir / "object.obj").string() + " --sequence " + (dir / "seq").string() +
                        " --out " + (dir / "out.csv").string() + " --resolution 80x60 --init \"0 0 0.8 1 0 0 0\"",
                    dir / "log.txt");
  INFO(output);
  REQUIRE(status == 0);
  // Ground truth is still known from the sequence, so the error columns stay.
  CHECK(test::lines_of(dir / "out.csv")[0].find("err_t_mm") != std::string::npos);
}

TEST_CASE("track --init-global and --init-box find the object without a pose", "[cli][global]") {
  const auto dir = test::write_cli_sequence("cli_track_global", 4);
  for (const std::string start : {"--init-global", "--init-box \"40 20 120 100\""}) {
    const auto [status, output] =
        test::run_cli("track --mesh " + (dir / "object.obj").string() + " --sequence " + (dir / "seq").string() +
                          " --out " + (dir / "out.csv").string() + " --resolution 80x60 " + start +
                          " --candidates-out " + (dir / "candidates.csv").string(),
                      dir / "log.txt");
    INFO(start << "\n" << output);
    REQUIRE(status == 0);
    CHECK(output.find("global initialization:") != std::string::npos);
    // The search's candidates, best first: the best one on the object (0.8 m away), supported.
    const auto candidates = test::lines_of(dir / "candidates.csv");
    REQUIRE(candidates.size() >= 2);
    CHECK(candidates[0] == "rank,score,confidence,tx,ty,tz,qw,qx,qy,qz");
    const auto best = test::cells_of(candidates[1]);
    REQUIRE(best.size() == 10);
    CHECK(best[0] == "1");
    CHECK(std::stod(best[2]) >= 0.5);
    CHECK(std::stod(best[5]) == Approx(0.8).margin(0.15));
    for (size_t i = 2; i < candidates.size(); ++i) {
      const auto row = test::cells_of(candidates[i]);
      REQUIRE(row.size() == 10);
      CHECK(std::stoul(row[0]) == i);
      CHECK(std::stod(row[2]) >= 0.0);
      CHECK(std::stod(row[2]) <= 1.0);
    }
    const auto lines = test::lines_of(dir / "out.csv");
    REQUIRE(lines.size() == 5);
    const auto cells = test::cells_of(lines.back());
    REQUIRE(cells.size() == 16);
    CHECK(std::stod(cells[10]) < 10.0);  // last frame within 1 cm of ground truth
    CHECK(cells[15] == "tracking");
  }
}

TEST_CASE("track explains every option", "[cli]") {
  const auto dir = test::temp_dir("cli_track_help");
  const auto [status, help] = test::run_cli("track --help", dir / "help.txt");
  CHECK(status == 0);
  for (const char* option : {"--mesh", "--sequence", "--out", "--object", "--backend", "--particles", "--resolution",
                             "--occlusion", "--seed", "--init-from-gt", "--init-perturb", "--init"})
    CHECK(help.find(option) != std::string::npos);
}

TEST_CASE("track refuses bad input with a reason and a non-zero exit code", "[cli][errors]") {
  const auto dir = test::write_cli_sequence("cli_track_errors", 2);
  const std::string base = "track --sequence " + (dir / "seq").string() + " --out " + (dir / "o.csv").string();
  const std::string mesh = " --mesh " + (dir / "object.obj").string();
  struct Case {
    std::string arguments, expected;
  };
  const Case cases[] = {
      {base + " --mesh " + (dir / "missing.obj").string() + " --init-from-gt", "does not exist"},
      {base + mesh, "--init"},
      {base + mesh + " --init-from-gt --particles 0", "particle count 0"},
      {base + mesh + " --init-from-gt --resolution 81x60", "81x60"},
      {base + mesh + " --init-from-gt --occlusion sometimes", "unknown occlusion mode 'sometimes'"},
      {base + mesh + " --init \"0 0 0.8 1 0\"", "takes 7 numbers"},
      {base + mesh + " --init-from-gt --backend quantum", "unknown backend 'quantum'"},
      {base + mesh + " --init-box \"50 40 20 60\"", "is empty"},
      {base + mesh + " --init-box \"100 50 170 90\"", "is not inside the 160x120 image"},
      {base + mesh + " --init-box \"1 2 3\"", "takes 4 numbers"},
      {base + mesh + " --init-from-gt --init-global", "exclude each other"},
      {base + mesh + " --init-from-gt --candidates-out " + (dir / "c.csv").string(),
       "give --init-global or --init-box"},
      {"track --sequence " + (dir / "nowhere").string() + " --out " + (dir / "o.csv").string() + mesh +
           " --init-from-gt",
       "does not exist"},
  };
  for (const Case& c : cases) {
    const auto [status, output] = test::run_cli(c.arguments, dir / "log.txt");
    INFO(c.arguments << "\n" << output);
    CHECK(status != 0);
    CHECK(output.find(c.expected) != std::string::npos);
  }
}
