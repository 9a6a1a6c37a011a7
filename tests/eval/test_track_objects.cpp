// Several objects in one run: `track` with --mesh/--object pairs (one Device, an object column, a row per
// object per frame, a summary entry per object, every object on the overlay), its refusals, and on ycbv-0000
// the last-frame ADD-S of each object with and without mutual occlusion against its own single-object run.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/sequence.hpp>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>

#include "cli_support.hpp"

using namespace depthtrack;

namespace {
// A row without its latency (wall time) cell: 16 cells, latency at 13.
std::vector<std::string> without_latency(std::vector<std::string> cells, size_t latency) {
  cells.erase(cells.begin() + static_cast<std::ptrdiff_t>(latency));
  return cells;
}
}  // namespace

TEST_CASE("track with two --mesh/--object pairs writes an object column and each object's own run", "[cli][multi]") {
  const auto dir = test::write_cli_sequence("cli_track_objects", 3);
  const std::string common = " --sequence " + (dir / "seq").string() +
                             " --resolution 80x60 --particles 60 --init-from-gt --init-perturb \"0.005 3\"";
  const std::string mesh = (dir / "object.obj").string();
  auto [status, output] =
      test::run_cli("track --mesh " + mesh + common + " --out " + (dir / "one.csv").string(), dir / "one.txt");
  INFO(output);
  REQUIRE(status == 0);
  std::tie(status, output) =
      test::run_cli("track --mesh " + mesh + " --object a --mesh " + mesh + " --object b" + common +
                        " --mutual-occlusion off --out " + (dir / "two.csv").string() + " --summary " +
                        (dir / "two.json").string() + " --overlay " + (dir / "overlay").string(),
                    dir / "two.txt");
  INFO(output);
  REQUIRE(status == 0);
  CHECK(output.find("2 objects, 3 frames") != std::string::npos);
  // An overlay picture per frame at the sensor's size, both objects drawn on it.
  for (const char* frame : {"000000", "000001", "000002"}) {
    std::ifstream png(dir / "overlay" / (std::string(frame) + ".png"), std::ios::binary);
    unsigned char header[24] = {};
    png.read(reinterpret_cast<char*>(header), sizeof header);
    CHECK(header[1] == 'P');
    CHECK(((header[18] << 8) | header[19]) == 160);
    CHECK(((header[22] << 8) | header[23]) == 120);
  }
  const auto one = test::lines_of(dir / "one.csv"), two = test::lines_of(dir / "two.csv");
  REQUIRE(one.size() == 4);
  REQUIRE(two.size() == 7);  // header, then a row per object per frame
  CHECK(two[0] == "object," + one[0]);
  for (size_t frame = 0; frame < 3; ++frame)
    for (size_t object = 0; object < 2; ++object) {
      const auto cells = test::cells_of(two[1 + 2 * frame + object]);
      REQUIRE(cells.size() == 17);
      CHECK(cells[0] == (object == 0 ? "a" : "b"));
      // The same start and seed as the one-object run, so the same estimates to the digit.
      CHECK(without_latency({cells.begin() + 1, cells.end()}, 13) ==
            without_latency(test::cells_of(one[1 + frame]), 13));
    }
  // The summary: an entry per object whose mean and largest ADD-S are those of its rows in the CSV.
  const auto summary = nlohmann::json::parse(test::text_of(dir / "two.json"));
  CHECK(summary.at("frames") == 3);
  REQUIRE(summary.at("objects").size() == 2);
  for (size_t object = 0; object < 2; ++object) {
    const auto& entry = summary.at("objects").at(object);
    CHECK(entry.at("object") == (object == 0 ? "a" : "b"));
    CHECK(entry.at("frames") == 3);
    double sum = 0, most = 0;
    for (size_t frame = 0; frame < 3; ++frame) {
      const double adds = std::stod(test::cells_of(two[1 + 2 * frame + object])[13]);
      sum += adds;
      most = std::max(most, adds);
    }
    CHECK(entry.at("mean_adds_mm").get<double>() == Approx(sum / 3).epsilon(1e-4));
    CHECK(entry.at("max_adds_mm").get<double>() == Approx(most).epsilon(1e-4));
  }
}

TEST_CASE("track with several objects refuses what it cannot do, naming it", "[cli][multi][errors]") {
  const auto dir = test::write_cli_sequence("cli_track_objects_errors", 2);
  const std::string mesh = " --mesh " + (dir / "object.obj").string();
  const std::string base = "track --sequence " + (dir / "seq").string() + " --out " + (dir / "o.csv").string();
  const std::pair<std::string, std::string> cases[] = {
      {base + mesh + " --object a" + mesh + " --init-from-gt", "in pairs: got 2 --mesh and 1 --object"},
      {base + mesh + " --object a" + mesh + " --object b --init-global", "--init-from-gt"},
      {base + mesh + " --object a" + mesh + " --object b --init-from-gt --bop-out " + (dir / "b.csv").string(),
       "--bop-out is for one object"},
      {base + mesh + " --object a" + mesh + " --object b --init-from-gt --mutual-occlusion maybe",
       "--mutual-occlusion takes on or off, not 'maybe'"},
  };
  for (const auto& [arguments, expected] : cases) {
    const auto [status, output] = test::run_cli(arguments, dir / "log.txt");
    INFO(arguments << "\n" << output);
    CHECK(status != 0);
    CHECK(output.find(expected) != std::string::npos);
  }
}

TEST_CASE("ycbv-0000: three objects in one run, with and without mutual occlusion, against their own runs",
          "[multi][accuracy]") {
  const auto clip = test::shared_data("sequences/ycbv-0000/gt.json");
  if (!clip) return;
  std::ifstream in(*clip);
  const auto json = nlohmann::json::parse(in);
  TrackerConfig config;  // reference, 80x60, 200 particles, seed 1
  const InitialSpread spread{0.01, 5 * std::numbers::pi / 180};
  std::vector<TrackedObject> objects;
  for (const auto& o : json["frames"][0]["objects"]) {
    const std::string name = o["name"];
    const auto mesh = test::shared_data("meshes/ycb/" + name + ".obj");
    if (!mesh) return;
    TrackedObject object{name, Mesh::load(*mesh), load_sequence(clip->parent_path(), name), {}};
    // 1 cm / 5 deg off the truth, as `track --init-perturb "0.01 5"` starts it.
    object.initial = perturb_pose(*object.sequence.frames.front().ground_truth, object.mesh.centre().cast<double>(),
                                  0.01, 5, config.seed);
    objects.push_back(std::move(object));
  }
  REQUIRE(objects.size() == 3);
  const auto with = track_objects(objects, config, spread, true);
  const auto without = track_objects(objects, config, spread, false);
  std::printf(
      "\nycbv-0000, 80x60, 200 particles, reference, start 1 cm / 5 deg off: last-frame ADD-S mm\n"
      "  object             own run   together, mutual occlusion off   on\n");
  for (size_t j = 0; j < objects.size(); ++j) {
    const auto own = track_sequence(objects[j].sequence, objects[j].mesh, config, objects[j].initial, spread);
    const double alone = own.back().adds, off = without[j].back().adds, on = with[j].back().adds;
    std::printf("  %-18s %7.2f %22.2f %17.2f\n", objects[j].name.c_str(), 1000 * alone, 1000 * off, 1000 * on);
    CHECK(off == alone);                    // the same trackers, only sharing a device and a frame
    CHECK(std::abs(on - alone) <= 0.0005);  // the bar: within 0.5 mm of the object's own run
    CHECK(on <= 0.010);
  }
}

TEST_CASE("depthtrack_bench --multi-objects prints one and three objects' median frames and their ratio",
          "[multi][bench]") {
  const std::string bench_dir = DEPTHTRACK_BENCH_DIR;
  if (bench_dir.empty()) return;  // DEPTHTRACK_BUILD_BENCH=OFF
  const auto dir = test::temp_dir("bench_multi_objects");
  const auto out = dir / "rows.csv";
  // The rows alone: without ../shared/data the bench says on stderr that it uses the built-in mesh.
  const std::string command = bench_dir + "/depthtrack_bench --multi-objects --particles 10 --frames 4 > " +
                              out.string() + " 2> " + (dir / "notes.txt").string();
  REQUIRE(std::system(command.c_str()) == 0);
  const auto lines = test::lines_of(out);
  std::map<std::string, std::map<std::string, double>> rows;  // test -> metric -> value
  for (size_t i = 1; i < lines.size(); ++i) {
    const auto cells = test::cells_of(lines[i]);
    REQUIRE(cells.size() >= 8);  // the device cell may hold commas: test, metric, unit, value are the last four
    const size_t n = cells.size();
    rows[cells[n - 4]][cells[n - 3]] = std::stod(cells[n - 1]);
  }
  REQUIRE(rows.size() == 2);
  for (const auto& [test, metrics] : rows) {
    INFO(test);
    CHECK(test.find("multi_object_") == 0);
    CHECK(test.find("_80x60_10p_occlusion_") != std::string::npos);
    const double one = metrics.at("one_object_ms"), three = metrics.at("three_objects_ms");
    CHECK(one > 0);
    CHECK(three > 0);
    CHECK(metrics.at("multi_object_ratio") == Approx(three / one).epsilon(1e-4));  // six significant digits printed
    // Each of the three alone, the first the one object above, and three over their mean.
    const double alone[3] = {metrics.at("object0_alone_ms"), metrics.at("object1_alone_ms"),
                             metrics.at("object2_alone_ms")};
    CHECK(alone[0] == Approx(one).epsilon(1e-5));
    CHECK(alone[1] > 0);
    CHECK(alone[2] > 0);
    const double mean = (alone[0] + alone[1] + alone[2]) / 3;
    CHECK(metrics.at("one_object_mean_ms") == Approx(mean).epsilon(1e-4));
    CHECK(metrics.at("multi_object_ratio_to_mean") == Approx(three / mean).epsilon(1e-4));
    const double serial = metrics.at("three_objects_one_host_thread_ms");
    CHECK(serial > 0);
    CHECK(metrics.at("one_host_thread_ratio") == Approx(serial / one).epsilon(1e-4));
    // Each stage's median, for one object and three; the masks only with mutual occlusion and several objects.
    for (const char* stage : {"working", "enqueue", "collect", "confidence", "confidence_sum", "steps_sum"}) {
      INFO(stage);
      CHECK(metrics.at(std::string("one_object_") + stage + "_ms") >= 0);
      CHECK(metrics.at(std::string("three_objects_") + stage + "_ms") > 0);
    }
    CHECK(metrics.at("one_object_masks_ms") == 0);
    const bool occlusion = test.find("occlusion_on") != std::string::npos;
    CHECK((metrics.at("three_objects_masks_ms") > 0) == occlusion);
  }
}
