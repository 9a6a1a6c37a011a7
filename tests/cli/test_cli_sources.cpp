// track reads frames from a stream (stdin through a pipe, a named pipe), float32 depth files, ViSP's simulated
// layout and a --frames range: each gives the estimates of the same frames read from a PNG folder.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <bit>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <depthtrack/sequence.hpp>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_support.hpp"
#include "io/visp_simulated_sequence.hpp"

using namespace depthtrack;
namespace fs = std::filesystem;

namespace {

void put_le(std::string& out, uint32_t bits, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((bits >> (8 * i)) & 0xff));
}

// The sequence as a raw depth stream: even frames float32 metres, odd frames uint16 units recovered from the
// PNG's (so that both decode to the very floats the PNG folder gives).
std::string raw_stream_of(const Sequence& s) {
  char header[160];
  std::snprintf(header, sizeof header, "depthtrack-raw-depth 1 %d %d %.17g %.17g %.17g %.17g\n", s.camera.width,
                s.camera.height, s.camera.fx, s.camera.fy, s.camera.cx, s.camera.cy);
  std::string out = header;
  for (size_t i = 0; i < s.frames.size(); ++i) {
    const DepthImage depth = s.load_depth(i);
    char line[96];
    if (i % 2 == 0) {
      std::snprintf(line, sizeof line, "%.17g f32\n", s.frames[i].timestamp);
      out += line;
      for (float z : depth.data()) put_le(out, std::bit_cast<uint32_t>(DepthImage::is_valid(z) ? z : 0.0f), 4);
    } else {
      std::snprintf(line, sizeof line, "%.17g u16 %.17g\n", s.frames[i].timestamp, s.metres_per_unit);
      out += line;
      for (float z : depth.data())
        put_le(out, DepthImage::is_valid(z) ? static_cast<uint32_t>(std::lround(z / s.metres_per_unit)) : 0u, 2);
    }
  }
  return out;
}

std::string pose_text(const Pose& p) {
  char text[256];
  std::snprintf(text, sizeof text, "\"%.17g %.17g %.17g %.17g %.17g %.17g %.17g\"", p.translation.x(),
                p.translation.y(), p.translation.z(), p.rotation.w(), p.rotation.x(), p.rotation.y(), p.rotation.z());
  return text;
}

std::string track_args(const fs::path& dir, const std::string& frames_from, const std::string& out,
                       const std::string& start) {
  return "track --mesh " + (dir / "object.obj").string() + " " + frames_from + " --out " + (dir / out).string() +
         " --resolution 80x60 --particles 100 --seed 3 " + start;
}

// The first columns of each row: frame, timestamp, pose and ESS (the estimate, not the scoring).
std::vector<std::string> estimates(const fs::path& csv) {
  std::vector<std::string> rows;
  for (const auto& line : test::lines_of(csv)) {
    const auto cells = test::cells_of(line);
    std::string row;
    for (size_t k = 0; k < 10 && k < cells.size(); ++k) row += cells[k] + ",";
    rows.push_back(row);
  }
  return rows;
}

// Runs a shell command line (the CLI behind a pipe); its exit status.
int shell(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST_CASE("track --source raw:- tracks frames piped in as the same frames read from their folder", "[cli][source]") {
  const auto dir = test::write_cli_sequence("cli_source_stdin", 5);
  const Sequence s = load_sequence(dir / "seq");
  std::ofstream(dir / "stream.raw", std::ios::binary) << raw_stream_of(s);
  const std::string start = "--init " + pose_text(*s.frames.front().ground_truth);

  const auto [status, output] =
      test::run_cli(track_args(dir, "--sequence " + (dir / "seq").string(), "folder.csv", start), dir / "folder.txt");
  INFO(output);
  REQUIRE(status == 0);
  const std::string piped = "cat " + (dir / "stream.raw").string() + " | " + DEPTHTRACK_CLI + " " +
                            track_args(dir, "--source raw:-", "stdin.csv", start) + " > " +
                            (dir / "stdin.txt").string() + " 2>&1";
  const int piped_status = shell(piped);
  INFO(test::text_of(dir / "stdin.txt"));
  REQUIRE(piped_status == 0);

  const auto folder = estimates(dir / "folder.csv"), stdin_rows = estimates(dir / "stdin.csv");
  REQUIRE(folder.size() == 6);
  CHECK(stdin_rows == folder);
  // The stream carries no ground truth, so no error columns; the folder run's say the poses are tracked.
  CHECK(test::lines_of(dir / "stdin.csv")[0].find("err_t_mm") == std::string::npos);
  for (size_t i = 1; i < 6; ++i) CHECK(std::stod(test::cells_of(test::lines_of(dir / "folder.csv")[i])[10]) < 10.0);
}

TEST_CASE("track --source raw:FIFO reads a named pipe as it is written", "[cli][source]") {
  const auto dir = test::write_cli_sequence("cli_source_fifo", 4);
  const Sequence s = load_sequence(dir / "seq");
  const fs::path fifo = dir / "frames.fifo";
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  const std::string bytes = raw_stream_of(s);
  // The writer waits (up to a minute) for the reader to open the pipe, then writes frame by frame.
  std::thread writer([&] {
    int fd = -1;
    for (int tries = 0; tries < 600 && fd < 0; ++tries) {
      fd = open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
      if (fd < 0) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    if (fd < 0) return;
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    for (size_t done = 0; done < bytes.size();) {
      const ssize_t n = write(fd, bytes.data() + done, std::min<size_t>(4096, bytes.size() - done));
      if (n <= 0) break;
      done += static_cast<size_t>(n);
    }
    close(fd);
  });
  const std::string start = "--init " + pose_text(*s.frames.front().ground_truth);
  const auto [status, output] =
      test::run_cli(track_args(dir, "--source raw:" + fifo.string(), "fifo.csv", start), dir / "fifo.txt");
  writer.join();
  INFO(output);
  REQUIRE(status == 0);
  const auto [folder_status, folder_output] = test::run_cli(
      track_args(dir, "--source folder:" + (dir / "seq").string(), "folder.csv", start), dir / "folder.txt");
  REQUIRE(folder_status == 0);
  const auto rows = estimates(dir / "fifo.csv");
  CHECK(rows.size() == 5);
  CHECK(rows == estimates(dir / "folder.csv"));
}

TEST_CASE("track reads float32 depth files (.f32) as the PNGs they were made from", "[cli][source]") {
  const auto dir = test::write_cli_sequence("cli_source_f32", 4);
  Sequence s = load_sequence(dir / "seq");
  for (size_t i = 0; i < s.frames.size(); ++i) {
    std::string bytes;
    const DepthImage depth = s.load_depth(i);
    for (float z : depth.data()) put_le(bytes, std::bit_cast<uint32_t>(DepthImage::is_valid(z) ? z : 0.0f), 4);
    s.frames[i].depth_path = dir / "f32" / (s.frames[i].name + "-depth.f32");
    fs::create_directories(dir / "f32");
    std::ofstream(s.frames[i].depth_path, std::ios::binary) << bytes;
  }
  write_sequence_manifest(dir / "f32", s);
  for (const auto& [folder, csv] : {std::pair{"seq", "png.csv"}, {"f32", "f32.csv"}}) {
    const auto [status, output] =
        test::run_cli(track_args(dir, "--sequence " + (dir / folder).string(), csv, "--init-from-gt"), dir / "log.txt");
    INFO(output);
    REQUIRE(status == 0);
  }
  CHECK(test::lines_of(dir / "f32.csv").size() == 5);
  // Every column, the errors against ground truth included.
  const auto png_lines = test::lines_of(dir / "png.csv"), f32_lines = test::lines_of(dir / "f32.csv");
  CHECK(estimates(dir / "f32.csv") == estimates(dir / "png.csv"));
  for (size_t i = 1; i < png_lines.size(); ++i)
    CHECK(test::cells_of(f32_lines[i])[10] == test::cells_of(png_lines[i])[10]);
}

TEST_CASE("track reads ViSP's simulated layout as it reads the same frames converted", "[cli][source][visp]") {
  const auto dir = test::write_cli_sequence("cli_source_visp", 4);
  const Sequence s = load_sequence(dir / "seq");
  // ViSP's files: depth at 1/32768 m per unit, the colour camera's poses (5 cm along +x of the depth camera's).
  const fs::path visp = dir / "visp";
  for (const char* sub : {"Depth", "CameraPose", "Config"}) fs::create_directories(visp / sub);
  const Pose depth_from_colour(Eigen::Vector3d(-0.05, 0, 0), Eigen::Quaterniond::Identity());
  for (size_t i = 0; i < s.frames.size(); ++i) {
    const DepthImage depth = s.load_depth(i);
    std::string bytes;
    put_le(bytes, static_cast<uint32_t>(depth.height()), 4);
    put_le(bytes, static_cast<uint32_t>(depth.width()), 4);
    for (float z : depth.data()) {
      const long units = DepthImage::is_valid(z) ? std::lround(z * 32768.0) : 0;
      put_le(bytes, units <= 65535 ? static_cast<uint32_t>(units) : 0u, 2);  // beyond 2 m: no measurement
    }
    char name[64];
    std::snprintf(name, sizeof name, "Depth_%04zu.bin", i + 1);
    std::ofstream(visp / "Depth" / name, std::ios::binary) << bytes;
    std::snprintf(name, sizeof name, "Camera_%03zu.txt", i + 1);
    const Eigen::Matrix4d m = (depth_from_colour.inverse() * *s.frames[i].ground_truth).matrix();
    std::ofstream pose(visp / "CameraPose" / name);
    pose.precision(17);
    for (int r = 0; r < 4; ++r) pose << m(r, 0) << " " << m(r, 1) << " " << m(r, 2) << " " << m(r, 3) << "\n";
  }
  // ViSP's simulator counts pixel centres from 0.5 (VispSimulatedImport::pixel_centre): the same camera.
  std::ofstream(visp / "Config" / "object_depth.xml")
      << "<conf><camera><px>" << s.camera.fx << "</px><py>" << s.camera.fy << "</py><u0>" << s.camera.cx + 0.5
      << "</u0><v0>" << s.camera.cy + 0.5 << "</v0></camera></conf>\n";
  io::import_visp_simulated_sequence(visp, dir / "converted", io::castle_options());

  // The same start for both (the converted manifest holds the truth as a matrix, read back to the last bit
  // or not).
  const std::string start = "--init " + pose_text(*s.frames.front().ground_truth);
  for (const auto& [folder, csv] : {std::pair{"visp", "visp.csv"}, {"converted", "converted.csv"}}) {
    const auto [status, output] =
        test::run_cli(track_args(dir, "--sequence " + (dir / folder).string(), csv, start), dir / "log.txt");
    INFO(output);
    REQUIRE(status == 0);
  }
  const auto lines = test::lines_of(dir / "visp.csv"), converted = test::lines_of(dir / "converted.csv");
  REQUIRE(lines.size() == 5);
  REQUIRE(converted.size() == 5);
  CHECK(test::cells_of(lines[1])[0] == "000001");  // named by the files' numbers
  CHECK(estimates(dir / "visp.csv") == estimates(dir / "converted.csv"));
  // The truth read back through the offset is the synthetic truth: the errors stay small and are the
  // converted sequence's.
  for (size_t i = 1; i < lines.size(); ++i) {
    CHECK(std::stod(test::cells_of(lines[i])[10]) < 10.0);
    CHECK(std::stod(test::cells_of(lines[i])[10]) == Approx(std::stod(test::cells_of(converted[i])[10])));
  }
}

TEST_CASE("track --frames A:B tracks that range from its first frame's truth, and refuses bad ranges",
          "[cli][source]") {
  const auto dir = test::write_cli_sequence("cli_source_range", 6);
  const auto [status, output] = test::run_cli(
      track_args(dir, "--sequence " + (dir / "seq").string() + " --frames 2:5", "range.csv", "--init-from-gt"),
      dir / "log.txt");
  INFO(output);
  REQUIRE(status == 0);
  const auto lines = test::lines_of(dir / "range.csv");
  REQUIRE(lines.size() == 4);
  CHECK(test::cells_of(lines[1])[0] == "000002");
  CHECK(test::cells_of(lines[3])[0] == "000004");
  CHECK(std::stod(test::cells_of(lines[1])[1]) == Approx(2.0 / 30));
  CHECK(std::stod(test::cells_of(lines[1])[10]) < 10.0);  // started from frame 2's truth

  const auto s = load_sequence(dir / "seq");
  std::ofstream(dir / "stream.raw", std::ios::binary) << raw_stream_of(s);
  const auto [stream_status, stream_output] =
      test::run_cli(track_args(dir, "--source raw:" + (dir / "stream.raw").string() + " --frames 1:3", "stream.csv",
                               "--init " + pose_text(*s.frames[1].ground_truth)),
                    dir / "stream_log.txt");
  INFO(stream_output);
  REQUIRE(stream_status == 0);
  const auto stream_lines = test::lines_of(dir / "stream.csv");
  REQUIRE(stream_lines.size() == 3);
  CHECK(test::cells_of(stream_lines[1])[0] == "000001");

  for (const auto& [range, words] :
       std::vector<std::pair<std::string, std::string>>{{"4:2", "the range is empty"},
                                                        {"2:99", "reaches past the sequence's 6 frames"},
                                                        {"x:3", "'x' is not a whole number"},
                                                        {"3", "is not A:B"}}) {
    const auto [bad_status, bad_output] = test::run_cli(
        track_args(dir, "--sequence " + (dir / "seq").string() + " --frames " + range, "bad.csv", "--init-from-gt"),
        dir / "bad.txt");
    INFO(range << "\n" << bad_output);
    CHECK(bad_status != 0);
    CHECK(bad_output.find(words) != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "bad.csv"));
  }
}

TEST_CASE("track refuses what a stream cannot give, and a source kind it does not know", "[cli][source][errors]") {
  const auto dir = test::write_cli_sequence("cli_source_errors", 2);
  for (const auto& [args, words] : std::vector<std::pair<std::string, std::string>>{
           {"--source raw:- --init-from-gt", "--init-from-gt needs the first frame's ground truth"},
           {"--source raw:- --init-global --overlay " + (dir / "o").string(), "--overlay is for a sequence folder"},
           {"--source camera:0 --init-global", "unknown kind 'camera' (known: folder, raw"},
           {"--sequence " + (dir / "seq").string() + " --source raw:- --init-global", "exclude each other"},
           {"--init-global", "give the frames: --sequence DIR or --source"}}) {
    const auto [status, output] = test::run_cli(track_args(dir, args, "out.csv", "") + " < /dev/null", dir / "log.txt");
    INFO(args << "\n" << output);
    CHECK(status != 0);
    CHECK(output.find(words) != std::string::npos);
  }
}
