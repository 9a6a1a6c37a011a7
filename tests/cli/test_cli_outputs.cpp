// What track writes besides the pose: ADD-S per frame, the JSON summary, ROS quaternion order, and
// what info --json reports.
#include <catch2/catch.hpp>
#include <depthtrack/evaluation.hpp>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "compute/queue.hpp"

using namespace depthtrack;

namespace {
std::string track_args(const std::filesystem::path& dir, const std::string& out) {
  return "track --mesh " + (dir / "object.obj").string() + " --sequence " + (dir / "seq").string() + " --out " +
         (dir / out).string() + " --resolution 80x60 --particles 100 --seed 3";
}
}  // namespace

TEST_CASE("track's adds_mm is the ADD-S of the row's pose, and --summary the run's means and maxima", "[cli]") {
  const auto dir = test::write_cli_sequence("cli_outputs_summary", 5);
  const auto [status, output] = test::run_cli(
      track_args(dir, "out.csv") + " --init-from-gt --summary " + (dir / "summary.json").string(), dir / "log.txt");
  INFO(output);
  REQUIRE(status == 0);
  const auto lines = test::lines_of(dir / "out.csv");
  REQUIRE(lines.size() == 6);
  const auto header = test::cells_of(lines[0]);
  REQUIRE(header.size() == 16);
  CHECK(header[10] == "err_t_mm");
  CHECK(header[11] == "err_r_deg");
  CHECK(header[12] == "adds_mm");
  CHECK(header[13] == "latency_ms");

  const Sequence seq = load_sequence(dir / "seq");
  const AddsMetric adds(builtin_demo_mesh());
  double sum_t = 0, max_t = 0, sum_adds = 0, max_r = 0;
  for (size_t i = 1; i < lines.size(); ++i) {
    const auto c = test::cells_of(lines[i]);
    const Pose pose({std::stod(c[2]), std::stod(c[3]), std::stod(c[4])},
                    Eigen::Quaterniond(std::stod(c[5]), std::stod(c[6]), std::stod(c[7]), std::stod(c[8])));
    const double expected_adds = 1000 * adds(pose, *seq.frames[i - 1].ground_truth);
    CHECK(std::stod(c[12]) == Approx(expected_adds).epsilon(1e-4));
    sum_t += std::stod(c[10]);
    max_t = std::max(max_t, std::stod(c[10]));
    max_r = std::max(max_r, std::stod(c[11]));
    sum_adds += std::stod(c[12]);
  }
  const auto summary_lines = test::lines_of(dir / "summary.json");
  REQUIRE(summary_lines.size() == 1);
  const auto j = nlohmann::json::parse(summary_lines[0]);
  CHECK(j["frames"] == 5);
  CHECK(j["backend"] == "reference");
  CHECK(j["particles"] == 100);
  CHECK(j["resolution"] == "80x60");
  CHECK(j["mean_err_t_mm"].get<double>() == Approx(sum_t / 5).epsilon(1e-6));
  CHECK(j["max_err_t_mm"].get<double>() == Approx(max_t).epsilon(1e-6));
  CHECK(j["max_err_r_deg"].get<double>() == Approx(max_r).epsilon(1e-6));
  CHECK(j["mean_adds_mm"].get<double>() == Approx(sum_adds / 5).epsilon(1e-6));
  CHECK(j["fps"].get<double>() == Approx(5 / j["seconds"].get<double>()));
}

TEST_CASE("track --quaternion xyzw reads --init and writes the CSV in ROS order", "[cli]") {
  const auto dir = test::write_cli_sequence("cli_outputs_quaternion", 3);
  const Pose start = *load_sequence(dir / "seq").frames[0].ground_truth;
  const Eigen::Vector3d t = start.translation;
  const Eigen::Quaterniond q = start.rotation;
  auto numbers = [](std::initializer_list<double> values) {
    std::ostringstream s;
    s.precision(12);
    for (double v : values) s << v << " ";
    return s.str();
  };
  const auto [wxyz_status, wxyz_log] = test::run_cli(
      track_args(dir, "wxyz.csv") + " --init \"" + numbers({t.x(), t.y(), t.z(), q.w(), q.x(), q.y(), q.z()}) + "\"",
      dir / "log.txt");
  REQUIRE(wxyz_status == 0);
  const auto [xyzw_status, xyzw_log] =
      test::run_cli(track_args(dir, "xyzw.csv") + " --quaternion xyzw --init \"" +
                        numbers({t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()}) + "\"",
                    dir / "log.txt");
  INFO(xyzw_log);
  REQUIRE(xyzw_status == 0);
  const auto a = test::lines_of(dir / "wxyz.csv"), b = test::lines_of(dir / "xyzw.csv");
  REQUIRE(a.size() == 4);
  REQUIRE(b.size() == 4);
  CHECK(test::cells_of(b[0])[5] == "qx");
  CHECK(test::cells_of(b[0])[8] == "qw");
  // The same start gives the same track: the components are only reordered.
  for (size_t i = 1; i < a.size(); ++i) {
    const auto ca = test::cells_of(a[i]), cb = test::cells_of(b[i]);
    CHECK(std::stod(cb[8]) == Approx(std::stod(ca[5])).margin(1e-7));  // w
    CHECK(std::stod(cb[5]) == Approx(std::stod(ca[6])).margin(1e-7));  // x
    CHECK(std::stod(cb[6]) == Approx(std::stod(ca[7])).margin(1e-7));  // y
    CHECK(std::stod(cb[7]) == Approx(std::stod(ca[8])).margin(1e-7));  // z
  }
  const auto [bad_status, bad] =
      test::run_cli(track_args(dir, "x.csv") + " --init-from-gt --quaternion zyxw", dir / "log.txt");
  CHECK(bad_status == 1);
  CHECK(bad.find("--quaternion 'zyxw' is neither wxyz") != std::string::npos);
}

TEST_CASE("info --json lists every compute device and GL path", "[cli]") {
  const auto dir = test::temp_dir("cli_outputs_info_json");
  const auto [status, output] = test::run_cli("info --json", dir / "info.json");
  INFO(output);
  REQUIRE(status == 0);
  const auto j = nlohmann::json::parse(output);
  size_t listed = 0;
  for (const char* backend : {"opencl", "cuda"}) {
    REQUIRE(j.contains(backend));
    const auto& devices = j[backend]["devices"];
    listed += devices.size();
    if (devices.empty()) CHECK(!j[backend]["unavailable"].get<std::string>().empty());
    for (const auto& d : devices) CHECK(d.contains("atlas_handoff") != d.contains("atlas_gl_unavailable"));
  }
  CHECK(listed == compute::list_devices().size());
#ifdef DEPTHTRACK_WITH_GL
  REQUIRE(j["gl"].size() == 3);
  CHECK(j["gl"][0]["path"] == "egl-device");
#else
  REQUIRE(j["gl"].size() == 1);
  CHECK(j["gl"][0]["unavailable"].get<std::string>().find("DEPTHTRACK_WITH_GL=OFF") != std::string::npos);
#endif
}
