// The depthtrack eval contract: a table row per case whose figures follow from its frames CSV, the summary,
// the reliability table, and clear refusals.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"

using namespace depthtrack;

namespace {

std::vector<std::string> words_of(const std::string& line) {
  std::stringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

struct CsvFrame {
  std::string frame, status, within;
  double timestamp = 0, adds_mm = 0, confidence = 0;
  std::string d2, dof, within_95;    // the covariance's check, empty without one
  std::vector<std::string> axis_d2;  // x, y, z, rx, ry, rz: empty without a check or where undetermined
};

// The frames CSV's rows by case, in order.
std::map<std::string, std::vector<CsvFrame>> frames_by_case(const std::filesystem::path& path) {
  const auto lines = test::lines_of(path);
  REQUIRE(!lines.empty());
  CHECK(lines[0] ==
        "object,case,frame,timestamp,adds_mm,confidence,status,within_tolerance,covariance_d2,covariance_dof,within_95,"
        "axis_d2_x,axis_d2_y,axis_d2_z,axis_d2_rx,axis_d2_ry,axis_d2_rz");
  std::map<std::string, std::vector<CsvFrame>> cases;
  for (size_t i = 1; i < lines.size(); ++i) {
    const auto c = test::cells_of(lines[i]);
    REQUIRE(c.size() == 17);
    CHECK(c[0] == "object");
    cases[c[1]].push_back({c[2], c[6], c[7], std::stod(c[3]), std::stod(c[4]), std::stod(c[5]), c[8], c[9], c[10],
                           std::vector<std::string>(c.begin() + 11, c.end())});
  }
  return cases;
}

}  // namespace

TEST_CASE("eval prints a row per case whose figures its frames CSV reproduces", "[cli][eval]") {
  const auto dir = test::write_cli_sequence("cli_eval", 12);
  const auto [status, output] = test::run_cli(
      "eval --sequence " + (dir / "seq").string() + " --mesh " + (dir / "object.obj").string() +
          " --cases perturbed,gap --seeds 1 --gaps 0.5 --gap-before 3 --resolution 80x60 --particles 100 --seed 4"
          " --frames-out " +
          (dir / "frames.csv").string(),
      dir / "log.txt");
  INFO(output);
  REQUIRE(status == 0);
  const auto cases = frames_by_case(dir / "frames.csv");
  REQUIRE(cases.size() == 2);
  REQUIRE(cases.count("perturbed-1") == 1);
  REQUIRE(cases.count("gap+0.5s") == 1);

  std::stringstream lines(output);
  size_t rows = 0, wrong_total = 0, coverage_rows = 0;
  bool header = false, summary = false;
  for (std::string line; std::getline(lines, line);) {
    const auto w = words_of(line);
    if (w.size() >= 12 && w[0] == "object" && w[1] == "case") {
      header = true;
      CHECK(w[2] == "frames");
      CHECK(w[3] == "adds_mm");
      CHECK(w[4] == "auc");
      CHECK(w[9] == "conf_wrong");
      continue;
    }
    if (w.size() >= 12 && w[0] == "object" && cases.count(w[1])) {
      ++rows;
      const auto& frames = cases.at(w[1]);
      INFO(line);
      REQUIRE(frames.size() == 12);
      CHECK(std::stoul(w[2]) == 12);
      // Independently from the CSV: mean ADD-S, its AUC over 0-100 mm, the last frame's, the status counts,
      // confident-wrong frames (> 20 mm, tracking, confidence >= 0.5).
      double sum = 0, area = 0;
      size_t tracking = 0, lost = 0, no_data = 0, wrong = 0, false_lost = 0;
      for (const CsvFrame& f : frames) {
        sum += f.adds_mm;
        area += std::max(0.0, 1.0 - f.adds_mm / 100.0);
        tracking += f.status == "tracking";
        lost += f.status == "lost";
        no_data += f.status == "no-data";
        wrong += f.adds_mm > 20.0 && f.status == "tracking" && f.confidence >= 0.5;
        false_lost += f.status == "lost" && f.within == "1";
        // The built-in object is over 16 cm across: its tolerance is the 10 mm cap.
        CHECK(f.within == (f.adds_mm <= 10.0 ? "1" : "0"));
      }
      CHECK(std::stod(w[3]) == Approx(sum / 12).margin(0.006));
      CHECK(std::stod(w[4]) == Approx(area / 12).margin(0.0006));
      CHECK(std::stod(w[5]) == Approx(frames.back().adds_mm).margin(0.006));
      CHECK(std::stoul(w[6]) == tracking);
      CHECK(std::stoul(w[7]) == lost);
      CHECK(std::stoul(w[8]) == no_data);
      CHECK(tracking + lost + no_data == 12);
      CHECK(std::stoul(w[9]) == wrong);
      wrong_total += wrong;
      CHECK(std::stod(w[10]) >= 0.0);  // seconds
      if (w[1] == "perturbed-1") {
        CHECK(w[11] == "false_lost=" + std::to_string(false_lost));
      } else {
        // Every frame from 5 after the gap (index 3 + 5) on within 10 mm or lost.
        bool recovered = true;
        for (size_t i = 8; i < frames.size(); ++i)
          recovered = recovered && (frames[i].adds_mm <= 10.0 || frames[i].status == "lost");
        CHECK(w[11] == std::string("recovered=") + (recovered ? "yes" : "no"));
      }
      // The clip runs at 30 Hz; the gap case's clock jumps by 0.5 s from frame 3 on.
      for (size_t i = 0; i < frames.size(); ++i)
        CHECK(frames[i].timestamp == Approx(i / 30.0 + (w[1] == "gap+0.5s" && i >= 3 ? 0.5 : 0.0)).margin(1e-6));
    }
    if (w.size() == 7 && w[0] == "object" && cases.count(w[1])) {  // the covariance's coverage row
      ++coverage_rows;
      INFO(line);
      size_t checked = 0, inside = 0, no_region = 0;
      for (const CsvFrame& f : cases.at(w[1])) {
        // No region: a lost or barely supported frame's covariance determines nothing.
        if (f.within_95.empty()) {
          ++no_region;
          for (const std::string& a : f.axis_d2) CHECK(a.empty());
          continue;
        }
        // A determined axis' own share is a square, and some axis of a region is determined.
        size_t axes = 0;
        for (const std::string& a : f.axis_d2)
          if (!a.empty()) {
            CHECK(std::stod(a) >= 0.0);
            ++axes;
          }
        CHECK(axes >= 1);
        ++checked;
        inside += f.within_95 == "1";
        // Inside exactly when d2 is at most the chi-squared 95 % quantile of its degrees of freedom.
        const double quantile[6] = {3.841459, 5.991465, 7.814728, 9.487729, 11.070498, 12.591587};
        const int dof = std::stoi(f.dof);
        REQUIRE(dof >= 1);
        REQUIRE(dof <= 6);
        CHECK((std::stod(f.d2) <= quantile[dof - 1]) == (f.within_95 == "1"));
      }
      // Refinement is on: every frame with ground truth has a covariance, with a region unless lost.
      CHECK(checked + no_region == 12);
      CHECK(std::stoul(w[2]) == checked);
      CHECK(std::stoul(w[3]) == inside);
      if (checked > 0) CHECK(std::stod(w[4]) == Approx(static_cast<double>(inside) / checked).margin(0.0006));
      CHECK(std::stoul(w[6]) == no_region);
    }
    if (line.rfind("summary:", 0) == 0) {
      summary = true;
      CHECK(line.find("confident-wrong frames " + std::to_string(wrong_total) + ";") != std::string::npos);
      CHECK(line.find("box starts ending within 10 mm 0 of 0") != std::string::npos);
      CHECK(line.find(" of 1") != std::string::npos);  // the one gap case
    }
  }
  CHECK(header);
  CHECK(rows == 2);
  CHECK(coverage_rows == 2);
  CHECK(summary);
  CHECK(output.find("confidence reliability over 24 frames") != std::string::npos);
  CHECK(output.find("expected calibration error") != std::string::npos);
  CHECK(output.find("object: mesh") != std::string::npos);
  CHECK(output.find("tolerance 10.00 mm") != std::string::npos);
}

TEST_CASE("eval refuses bad input with a reason before tracking", "[cli][eval][errors]") {
  const auto dir = test::write_cli_sequence("cli_eval_errors", 4);
  const std::string base = "eval --sequence " + (dir / "seq").string() + " --resolution 80x60 --particles 50 ";
  const std::string mesh = "--mesh " + (dir / "object.obj").string() + " ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {base + mesh + "--cases perturbed,wobble", "unknown case 'wobble'"},
      {base + mesh + "--cases gap --gap-before 4", "--gap-before 4 must name a frame after the first: 1 to 3"},
      {base + mesh + "--seeds 0", "--seeds must be at least 1"},
      {base + mesh + "--gaps 0.5,-1", "--gaps takes positive seconds"},
      {base, "give either --mesh FILE (with --object) or --mesh-dir DIR"},
      {base + "--mesh-dir " + dir.string(), "does not name its object"},
      {base + mesh + "--cases perturbed --frames-out " + (dir / "absent" / "f.csv").string(), "does not exist"},
      {base + mesh + "--cases perturbed --reliability " + (dir / "r.svg").string(), "must name a .png file"},
  };
  for (const auto& [arguments, message] : cases) {
    const auto [status, output] = test::run_cli(arguments, dir / "log.txt");
    INFO(arguments << "\n" << output);
    CHECK(status == 1);
    CHECK(output.find(message) != std::string::npos);
    CHECK(output.find("summary:") == std::string::npos);  // nothing was tracked
  }
  // Without an interpreter that has matplotlib, --reliability fails at once, saying what to install.
  const auto [status, output] = test::run_cli(base + mesh + "--reliability " + (dir / "r.png").string(),
                                              dir / "log.txt", "DEPTHTRACK_PYTHON=/nonexistent/python3");
  INFO(output);
  CHECK(status == 1);
  CHECK(output.find("needs python3 with matplotlib (/nonexistent/python3 was not found)") != std::string::npos);
  CHECK(output.find("summary:") == std::string::npos);
}

TEST_CASE("eval --reliability draws the diagram through depthtrack/plots.py", "[cli][eval]") {
  const auto dir = test::write_cli_sequence("cli_eval_reliability", 4);
  const auto [status, output] = test::run_cli(
      "eval --sequence " + (dir / "seq").string() + " --mesh " + (dir / "object.obj").string() +
          " --cases perturbed --seeds 1 --resolution 80x60 --particles 50 --reliability " + (dir / "r.png").string(),
      dir / "log.txt");
  if (status == 1 && output.find("needs python3 with matplotlib") != std::string::npos) {
    std::printf("SKIPPED: no python3 with matplotlib here\n");
    return;
  }
  INFO(output);
  REQUIRE(status == 0);
  std::ifstream png(dir / "r.png", std::ios::binary);
  char signature[8] = {};
  png.read(signature, 8);
  CHECK(std::string(signature + 1, 3) == "PNG");
  CHECK(output.find("4 frames, ECE") != std::string::npos);        // plots.py's own count
  CHECK_FALSE(std::filesystem::exists(dir / "r.png.frames.csv"));  // the rows it drew from are removed
}

TEST_CASE("eval: a failed diagram leaves the earlier --frames-out and picture as they were", "[cli][eval][outputs]") {
  const auto dir = test::write_cli_sequence("cli_eval_transaction", 4);
  // An interpreter that passes the matplotlib check and then fails to draw: the run fails after tracking.
  const auto python = dir / "failing-python";
  std::ofstream(python) << "#!/bin/sh\n[ \"$1\" = -c ] && exit 0\nexit 3\n";
  std::filesystem::permissions(python, std::filesystem::perms::owner_all);
  std::ofstream(dir / "frames.csv") << "earlier rows\n";
  std::ofstream(dir / "r.png") << "earlier picture\n";
  const auto [status, output] =
      test::run_cli("eval --sequence " + (dir / "seq").string() + " --mesh " + (dir / "object.obj").string() +
                        " --cases perturbed --seeds 1 --resolution 80x60 --particles 50 --frames-out " +
                        (dir / "frames.csv").string() + " --reliability " + (dir / "r.png").string(),
                    dir / "log.txt", "DEPTHTRACK_PYTHON=" + python.string());
  INFO(output);
  CHECK(status == 1);
  CHECK(output.find("drawing the figure failed") != std::string::npos);
  CHECK(test::text_of(dir / "frames.csv") == "earlier rows\n");
  CHECK(test::text_of(dir / "r.png") == "earlier picture\n");
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    CHECK(entry.path().filename().string().find(".partial") == std::string::npos);
}
