// depthtrack plot: tick choice, where a line lands, the panels a CSV's columns give, and bad CSVs.
#include <catch2/catch.hpp>
#include <fstream>

#include "cli_support.hpp"
#include "viz/line_plot.hpp"

using namespace depthtrack;
using viz::Rgb;

TEST_CASE("plot ticks are round steps covering the range", "[viz]") {
  CHECK(viz::nice_ticks(0, 7.3, 4) == std::vector<double>{0, 2, 4, 6});
  const auto small = viz::nice_ticks(0, 0.63, 6);  // step 0.105 rounds up to 0.2
  REQUIRE(small.size() == 4);
  CHECK(small[3] == Approx(0.6));
  CHECK(viz::nice_ticks(-3, 3, 3) == std::vector<double>{-2, 0, 2});
}

TEST_CASE("a plotted series passes through its data points", "[viz]") {
  std::vector<double> x, y;
  for (int i = 0; i <= 10; ++i) {
    x.push_back(i);
    y.push_back(i);
  }
  const Rgb red{200, 0, 0};
  const auto image = viz::plot_panels(x, "T", {{"P", {{"Y", y, red}}}}, 400, 200);
  CHECK(image.width() == 400);
  CHECK(image.height() == 256);
  // Plot area x 90..364, y 34..186; y axis 0..10.5: the point (5, 5) is at (227, 186 - 152 * 5 / 10.5).
  CHECK(image.at(227, 114) == red);
  CHECK(!(image.at(227, 60) == red));
  CHECK_THROWS_WITH(viz::plot_panels(x, "T", {{"P", {{"Y", {1, 2}, red}}}}), Catch::Contains("has 2 values for 11"));
}

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
  INFO(output);
  REQUIRE(status == 0);
  CHECK(output.find("5 panels, 5 frames") != std::string::npos);
  const auto image = viz::RgbImage::load_png(dir / "run.png");
  CHECK(image.width() == 960);
  CHECK(image.height() == 5 * 200 + 56);

  // A CSV without ground truth: the ESS alone.
  {
    std::ofstream csv(dir / "plain.csv");
    csv << "frame,timestamp,tx,ty,tz,qw,qx,qy,qz,ess\n000000,0,0,0,1,1,0,0,0,3\n000001,0.1,0,0,1,1,0,0,0,4\n";
  }
  const auto [plain_status, plain] =
      test::run_cli("plot " + (dir / "plain.csv").string() + " --out " + (dir / "plain.png").string(), dir / "log.txt");
  CHECK(plain_status == 0);
  CHECK(plain.find("1 panel, 2 frames") != std::string::npos);
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
    INFO(c.file << "\n" << output);
    CHECK(status == 1);
    CHECK(output.find(c.expected) != std::string::npos);
  }
}
