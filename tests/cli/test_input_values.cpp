// Values beyond sane bounds that used to pass with exit 0 and give wrong output: an implausible focal
// length, absurd timestamps, a NaN perturbation, a seed that wraps, a negative wall, a zero frame count.
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/sequence.hpp>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_support.hpp"
#include "support.hpp"

using namespace depthtrack;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

TEST_CASE("a focal length giving an implausible field of view is refused", "[camera][values]") {
  // 640 pixels over fx = 1e-300: 180 degrees; over 1e300: 0 degrees.
  CHECK_THROWS_WITH(Camera::make(640, 480, 1e-300, 525, 319.5, 239.5), Contains("fx") && Contains("field of view"));
  CHECK_THROWS_WITH(Camera::make(640, 480, 525, 1e300, 319.5, 239.5), Contains("fy") && Contains("field of view"));
  // 2 atan(640 / (2 * 36670)) = 1.0 degree; a 60-degree lens and the limits' inside pass.
  CHECK_THROWS(Camera::make(640, 480, 37000, 37000, 319.5, 239.5));
  CHECK_NOTHROW(Camera::make(640, 480, 36000, 27000, 319.5, 239.5));  // 1.02 degrees either way
  CHECK_NOTHROW(Camera::make(640, 480, 554, 554, 319.5, 239.5));
  CHECK_THROWS(Camera::make(640, 480, 2.7, 2.7, 319.5, 239.5));  // 2 atan(320 / 2.7) = 179.03 degrees
  CHECK_NOTHROW(Camera::make(640, 480, 2.9, 2.9, 319.5, 239.5));
}

TEST_CASE("sequence timestamps must be finite, within 1e10 s and less than a day apart", "[io][values]") {
  const auto dir = test::write_cli_sequence("limits_times", 3);
  const fs::path manifest = dir / "seq" / "sequence.json";
  const nlohmann::json original = nlohmann::json::parse(std::ifstream(manifest));
  const std::pair<double, std::string> cases[] = {{1e300, "outside the sane range"}, {1e6, "more than a day"}};
  for (const auto& [t, expected] : cases) {
    nlohmann::json edited = original;
    edited["frames"][2]["timestamp"] = t;
    std::ofstream(manifest) << edited.dump();
    CHECK_THROWS_WITH(load_sequence(dir / "seq"), Contains("frame '000002'") && Contains(expected));
  }
  // Unix-epoch seconds, as ROS stamps its messages, are real times.
  nlohmann::json epoch = original;
  for (size_t i = 0; i < epoch["frames"].size(); ++i) epoch["frames"][i]["timestamp"] = 1.765e9 + i / 30.0;
  std::ofstream(manifest) << epoch.dump();
  CHECK(load_sequence(dir / "seq").frames[2].timestamp == Approx(1.765e9 + 2 / 30.0));
  // BOP image ids give the times (30 Hz): ids 0 and 999,999,999 are 385 days apart.
  const auto scene = test::temp_dir("limits_bop_ids") / "000001";
  fs::create_directories(scene / "depth");
  DepthImage(4, 3).save_png(scene / "depth" / "000000.png", 0.0001);
  std::ofstream(scene / "scene_camera.json") << R"({"0": {"cam_K": [5, 0, 1.5, 0, 5, 1, 0, 0, 1], "depth_scale": 0.1},
      "999999999": {"cam_K": [5, 0, 1.5, 0, 5, 1, 0, 0, 1], "depth_scale": 0.1}})";
  std::ofstream(scene / "scene_gt.json") << "{}";
  CHECK_THROWS_WITH(load_sequence(scene), Contains("frame '999999999'") && Contains("more than a day"));
}

TEST_CASE("perturb_pose refuses a non-finite distance or angle instead of returning a NaN pose", "[eval][values]") {
  const Pose start({0, 0, 0.8}, Eigen::Quaterniond::Identity());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(perturb_pose(start, Eigen::Vector3d::Zero(), nan, 5, 1), InputError);
  CHECK_THROWS_WITH(perturb_pose(start, Eigen::Vector3d::Zero(), 0.01, INFINITY, 1), Contains("must be finite"));
  const Pose moved = perturb_pose(start, Eigen::Vector3d::Zero(), 0.01, 5, 1);
  CHECK((moved.translation - start.translation).norm() == Approx(0.01));
}

TEST_CASE("seeds out of range, negative wall depths and zero frame counts are refused on the command line",
          "[cli][values]") {
  const auto dir = test::temp_dir("limits_cli_values");
  const std::string synth = "synth --builtin --frames 1 --resolution 80x60 --out " + (dir / "s").string();
  const std::pair<std::string, std::string> cases[] = {
      {synth + " --seed -1", "--seed '-1' is not a whole number from 0 to 18446744073709551615"},
      {synth + " --seed 1e21", "--seed '1e21' is not a whole number"},
      {synth + " --seed 18446744073709551616", "--seed '18446744073709551616'"},
      {synth + " --background -1", "--background -1"},
      {synth + " --background nan", "is not a depth"},
      {"bench --test-grid --backend reference --frames 0 --out " + (dir / "b").string(), "--frames must be at least 3"},
      {"bench --test-grid --backend reference --frames -5 --out " + (dir / "b").string(), "got -5"},
      {"bench --test-grid --backend reference --max-seconds -1 --out " + (dir / "b").string(), "--max-seconds -1"},
      {"bench --test-grid --backend reference --max-seconds nan --out " + (dir / "b").string(), "is not a time limit"},
  };
  for (const auto& [arguments, expected] : cases) {
    const auto [status, output] = test::run_cli(arguments, dir / "log.txt");
    INFO(arguments << ": " << output);
    CHECK(status == 1);
    CHECK_THAT(output, Contains(expected));
  }
  CHECK_FALSE(fs::exists(dir / "s" / "sequence.json"));
  CHECK_FALSE(fs::exists(dir / "b" / "results.json"));
  // The largest seed is a seed; the object's name is kept in the manifest.
  const auto [status, output] = test::run_cli(synth + " --seed 18446744073709551615 --object mug", dir / "log.txt");
  INFO(output);
  REQUIRE(status == 0);
  CHECK(load_sequence(dir / "s").object == "mug");
  CHECK(nlohmann::json::parse(std::ifstream(dir / "s" / "sequence.json"))["object"] == "mug");
}

TEST_CASE("track refuses a seed that would wrap", "[cli][values]") {
  const auto dir = test::write_cli_sequence("limits_track_seed", 2);
  const auto [status, output] =
      test::run_cli("track --mesh " + (dir / "object.obj").string() + " --sequence " + (dir / "seq").string() +
                        " --out " + (dir / "o.csv").string() + " --init-from-gt --seed -1",
                    dir / "log.txt");
  CHECK(status == 1);
  CHECK_THAT(output, Contains("--seed '-1' is not a whole number"));
  CHECK_FALSE(fs::exists(dir / "o.csv"));
}
