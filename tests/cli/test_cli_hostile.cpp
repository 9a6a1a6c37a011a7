// depthtrack track on hostile input and output places: each is a clear error with a
// non-zero exit, or correct output; none is exit 0 with NaN rows or a cut file.
#include <catch2/catch.hpp>
#include <chrono>
#include <depthtrack/depth_image.hpp>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_support.hpp"
#include "device_support.hpp"
#include "support.hpp"

using namespace depthtrack;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

using test::text_of;

// track on the sequence in dir with extra arguments; the CSV goes to out unless the arguments name one.
std::pair<int, std::string> track(const fs::path& dir, const std::string& arguments,
                                  const std::string& out = "out.csv") {
  return test::run_cli("track --mesh " + (dir / "object.obj").string() + " --sequence " + (dir / "seq").string() +
                           " --resolution 80x60 --particles 30 --out " +
                           (out.front() == '/' ? out : (dir / out).string()) + " " + arguments,
                       dir / "log.txt");
}

}  // namespace

TEST_CASE("track --out /dev/full fails with a clear error instead of printing 'wrote'", "[cli][robustness]") {
  if (!fs::exists("/dev/full")) return;
  const auto dir = test::write_cli_sequence("cli_out_full", 2);
  const auto [status, output] = track(dir, "--init-from-gt", "/dev/full");
  INFO(output);
  CHECK(status == 1);
  CHECK_THAT(output, Contains("/dev/full") && Contains("failed writing"));
  CHECK_THAT(output, !Contains("wrote"));
}

TEST_CASE("track checks --out before tracking: a folder or a missing folder is refused at once", "[cli][robustness]") {
  const auto dir = test::write_cli_sequence("cli_out_place", 2);
  // Without the mesh the run would fail later: the --out check must come first.
  fs::remove(dir / "object.obj");
  const auto [folder_status, folder_output] = track(dir, "--init-from-gt", dir.string());
  CHECK(folder_status == 1);
  CHECK_THAT(folder_output, Contains("is a folder"));
  const auto [missing_status, missing_output] = track(dir, "--init-from-gt", (dir / "no/such/out.csv").string());
  CHECK(missing_status == 1);
  CHECK_THAT(missing_output, Contains("does not exist") && Contains("no/such"));
  CHECK_THAT(missing_output + folder_output, !Contains("object.obj"));
}

TEST_CASE("a failed track leaves an earlier CSV untouched and no partial file", "[cli][robustness]") {
  const auto dir = test::write_cli_sequence("cli_out_keep", 2);
  std::ofstream(dir / "out.csv") << "earlier results\n";
  // Fails after the CSV was opened: the start pose is not finite.
  const auto [status, output] = track(dir, "--init \"0 0 nan 1 0 0 0\"");
  INFO(output);
  CHECK(status == 1);
  CHECK(text_of(dir / "out.csv") == "earlier results\n");
  CHECK_FALSE(fs::exists(dir / "out.csv.partial"));
  // A run that succeeds replaces it, and leaves no partial file either.
  const auto [ok_status, ok_output] = track(dir, "--init-from-gt");
  INFO(ok_output);
  CHECK(ok_status == 0);
  CHECK_THAT(text_of(dir / "out.csv"), Contains("frame,timestamp"));
  CHECK_FALSE(fs::exists(dir / "out.csv.partial"));
}

TEST_CASE("a sensor dropout mid-sequence is tracked through: its row says no-data and the run succeeds",
          "[cli][robustness]") {
  const auto dir = test::write_cli_sequence("cli_dropout", 4);
  const auto frame = dir / "seq" / "depth_000002.png";
  REQUIRE(fs::exists(frame));
  DepthImage(160, 120).save_png(frame, 0.001);  // every pixel 0: no measurement
  const auto [status, output] = track(dir, "--init-from-gt");
  INFO(output);
  REQUIRE(status == 0);
  const std::string csv = text_of(dir / "out.csv");
  CHECK_THAT(csv, Contains("000002,") && Contains(",no-data\n"));
  CHECK_THAT(csv, !Contains("nan"));
  std::istringstream rows(csv);
  int no_data = 0, tracking = 0;
  for (std::string row; std::getline(rows, row);) {
    no_data += row.ends_with(",no-data");
    tracking += row.ends_with(",tracking");
  }
  CHECK(no_data == 1);
  CHECK(tracking == 3);
}

TEST_CASE("track refuses an absurd initial spread and a zero quaternion instead of writing NaN or q = 0 rows",
          "[cli][robustness]") {
  const auto dir = test::write_cli_sequence("cli_bad_start", 2);
  const auto [spread_status, spread_output] = track(dir, "--init-from-gt --init-spread \"1e300 1e300\"");
  CHECK(spread_status == 1);
  CHECK_THAT(spread_output, Contains("initial spread"));
  const auto [zero_status, zero_output] = track(dir, "--init \"0 0 0.8 0 0 0 0\"");
  CHECK(zero_status == 1);
  CHECK_THAT(zero_output, Contains("zero quaternion"));
  const auto [behind_status, behind_output] = track(dir, "--init \"0 0 -0.8 1 0 0 0\"");
  CHECK(behind_status == 1);
  CHECK_THAT(behind_output, Contains("behind"));
  CHECK_FALSE(fs::exists(dir / "out.csv"));
  CHECK_FALSE(fs::exists(dir / "out.csv.partial"));
}

TEST_CASE("track refuses a malformed occlusion window by name, and tracks with a good one", "[cli][robustness]") {
  const auto dir = test::write_cli_sequence("cli_window", 3);
  for (const char* bad : {"32", "32x-4", "wide"}) {
    const auto [status, output] = track(dir, std::string("--init-from-gt --occlusion-window ") + bad);
    INFO(bad << ": " << output);
    CHECK(status == 1);
    CHECK_THAT(output, Contains(std::string("--occlusion-window '") + bad + "' is not auto, full or WxH"));
  }
  CHECK_FALSE(fs::exists(dir / "out.csv"));
  const auto [status, output] = track(dir, "--init-from-gt --occlusion-window 24x16");
  INFO(output);
  CHECK(status == 0);
  CHECK(test::lines_of(dir / "out.csv").size() == 4);  // the header and three frames
}

TEST_CASE("track refuses a bad mesh simplification error by name, and tracks with a good one", "[cli][robustness]") {
  const auto dir = test::write_cli_sequence("cli_simplify", 3);
  for (const char* bad : {"-0.001", "nan", "2"}) {
    const auto [status, output] = track(dir, std::string("--init-from-gt --simplify-error ") + bad);
    INFO(bad << ": " << output);
    CHECK(status != 0);
    CHECK_THAT(output, Contains("simplif"));
  }
  CHECK_FALSE(fs::exists(dir / "out.csv"));
  const auto [status, output] = track(dir, "--init-from-gt --simplify-error 0.0005");
  INFO(output);
  CHECK(status == 0);
  CHECK(test::lines_of(dir / "out.csv").size() == 4);  // the header and three frames
}

TEST_CASE("the off-screen start (an object 10,000 km to the side) ends at once on the device, lost, exit 0",
          "[cli][robustness]") {
  // The device rasterizer looped over 2^31 columns per triangle (> 7 minutes for one particle). Its
  // time is a benchmark row (depthtrack_bench: offscreen_start); here, what the run ends with: every
  // frame tracked with confidence 0 (nothing of the object is drawn in the image), so every frame is
  // reported lost (a pose nothing supports is never `tracking`), exit 0 with every row written.
  if (!test::device_available()) return;
  const auto dir = test::write_cli_sequence("cli_offscreen", 3);
  const auto start = std::chrono::steady_clock::now();
  const auto [status, output] =
      test::run_cli("track --mesh " + (dir / "object.obj").string() + " --sequence " + (dir / "seq").string() +
                        " --resolution 80x60 --out " + (dir / "out.csv").string() +
                        " --init \"1e7 0 0.06 1 0 0 0\" --particles 1 --backend " + test::device_selector(),
                    dir / "log.txt");
  INFO(output);
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 60);  // a hang guard
  REQUIRE(status == 0);
  CHECK_THAT(output, Contains("lost in 3 of 3 frames"));
  const auto lines = test::lines_of(dir / "out.csv");
  REQUIRE(lines.size() == 4);
  const auto header = test::cells_of(lines[0]);
  REQUIRE(header.size() >= 2);
  CHECK(header[header.size() - 2] == "confidence");
  CHECK(header.back() == "status");
  for (size_t i = 1; i < lines.size(); ++i) {
    INFO(lines[i]);
    const auto cells = test::cells_of(lines[i]);
    REQUIRE(cells.size() == header.size());
    CHECK(std::stod(cells[2]) == Approx(1e7));  // tx: the estimate stays where it was started
    CHECK(std::stod(cells[cells.size() - 2]) == 0.0);
    CHECK(cells.back() == "lost");
  }
}
