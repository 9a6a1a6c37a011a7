// Every output of a command is checked before any work and replaced together at the end: a bad path,
// an output that names an input, or a failed write leaves each earlier file as it was.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <depthtrack/sequence.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>

#include "cli_support.hpp"
#include "support.hpp"
#include "viz/rgb_image.hpp"

using namespace depthtrack;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

using test::text_of;

std::pair<int, std::string> track(const fs::path& dir, const fs::path& sequence, const std::string& arguments) {
  return test::run_cli("track --mesh " + (dir / "object.obj").string() + " --sequence " + sequence.string() +
                           " --resolution 80x60 --particles 20 --init-from-gt " + arguments,
                       dir / "log.txt");
}

// Earlier results that a failed run must leave alone.
void write_earlier(const std::vector<fs::path>& files) {
  for (const auto& f : files) std::ofstream(f) << "earlier " << f.filename().string() << "\n";
}

void check_earlier(const std::vector<fs::path>& files) {
  for (const auto& f : files) {
    INFO(f);
    CHECK(text_of(f) == "earlier " + f.filename().string() + "\n");
    // No partial file of any writer is left beside it (the CSV writer's own included).
    for (const auto& entry : fs::directory_iterator(f.parent_path()))
      CHECK(entry.path().string().find(".partial") == std::string::npos);
  }
}

// The synthetic sequence of write_cli_sequence as a BOP scene (obj_id 1, poses in mm) beside it, and the
// mesh in millimetres as BOP ships its models; returns the scene folder.
fs::path bop_scene(const fs::path& dir) {
  const Sequence seq = load_sequence(dir / "seq");
  const fs::path scene = dir / "000001";
  fs::create_directories(scene / "depth");
  nlohmann::json cameras = nlohmann::json::object(), poses = nlohmann::json::object();
  const Camera& c = seq.camera;
  for (size_t i = 0; i < seq.frames.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "%06zu.png", i);
    fs::copy_file(seq.frames[i].depth_path, scene / "depth" / name);
    cameras[std::to_string(i)] = {{"cam_K", {c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1}},
                                  {"depth_scale", 1000 * seq.metres_per_unit}};
    const Pose& p = *seq.frames[i].ground_truth;
    const Eigen::Matrix3d r = p.rotation.toRotationMatrix();
    nlohmann::json rotation = nlohmann::json::array(), translation = nlohmann::json::array();
    for (int k = 0; k < 9; ++k) rotation.push_back(r(k / 3, k % 3));
    for (int k = 0; k < 3; ++k) translation.push_back(1000 * p.translation[k]);
    poses[std::to_string(i)] = {{{"cam_R_m2c", rotation}, {"cam_t_m2c", translation}, {"obj_id", 1}}};
  }
  std::ofstream(scene / "scene_camera.json") << cameras.dump();
  std::ofstream(scene / "scene_gt.json") << poses.dump();
  test::write_obj(dir / "object_mm.obj", builtin_demo_mesh(), 1000.0);
  return scene;
}

}  // namespace

TEST_CASE("a bad --summary or --bop-out path fails before tracking and leaves the earlier --out", "[cli][outputs]") {
  const auto dir = test::write_cli_sequence("safe_summary_path", 2);
  const std::vector<fs::path> earlier = {dir / "out.csv", dir / "s.json"};
  write_earlier(earlier);
  fs::remove(dir / "object.obj");  // the path checks must come before the mesh is read
  const auto [status, output] = track(
      dir, dir / "seq", "--out " + (dir / "out.csv").string() + " --summary " + (dir / "no/such/s.json").string());
  INFO(output);
  CHECK(status == 1);
  CHECK_THAT(output, Contains("--summary") && Contains("no/such") && Contains("does not exist"));
  CHECK_THAT(output, !Contains("object.obj"));
  check_earlier(earlier);
}

TEST_CASE("track: --summary and --bop-out on a full disk fail, leaving every earlier file as it was",
          "[cli][outputs]") {
  if (!fs::exists("/dev/full")) return;
  const auto dir = test::write_cli_sequence("safe_full", 2);
  const fs::path scene = bop_scene(dir);
  const std::vector<fs::path> earlier = {dir / "out.csv", dir / "bop.csv", dir / "s.json"};
  write_earlier(earlier);
  const std::string mesh = " --mesh " + (dir / "object_mm.obj").string();
  for (const std::string& full : {"--summary /dev/full --bop-out " + (dir / "bop.csv").string(),
                                  "--bop-out /dev/full --summary " + (dir / "s.json").string()}) {
    const auto [status, output] = test::run_cli("track" + mesh + " --sequence " + scene.string() +
                                                    " --object 1 --resolution 80x60 "
                                                    "--particles 20 --init-from-gt --out " +
                                                    (dir / "out.csv").string() + " " + full,
                                                dir / "log.txt");
    INFO(full << ": " << output);
    CHECK(status == 1);
    CHECK_THAT(output, Contains("failed writing '/dev/full'"));
    CHECK_THAT(output, !Contains("wrote"));
    check_earlier(earlier);
  }
  // The same run with every output in place writes them all.
  const auto [status, output] =
      test::run_cli("track" + mesh + " --sequence " + scene.string() +
                        " --object 1 --resolution 80x60 --particles 20 "
                        "--init-from-gt --out " +
                        (dir / "out.csv").string() + " --bop-out " + (dir / "bop.csv").string() + " --summary " +
                        (dir / "s.json").string(),
                    dir / "log.txt");
  INFO(output);
  REQUIRE(status == 0);
  CHECK(test::lines_of(dir / "out.csv").size() == 3);  // the header and two frames
  const auto bop = test::lines_of(dir / "bop.csv");
  REQUIRE(bop.size() == 3);
  CHECK(bop[0] == "scene_id,im_id,obj_id,score,R,t,time");
  CHECK(bop[2].rfind("1,1,1,", 0) == 0);  // scene 1, image 1, object 1
  CHECK(nlohmann::json::parse(text_of(dir / "s.json"))["frames"] == 2);
}

TEST_CASE("an output naming an input of the run is refused before anything is written", "[cli][outputs]") {
  const auto dir = test::write_cli_sequence("safe_inputs", 2);
  const fs::path manifest = dir / "seq" / "sequence.json", depth = dir / "seq" / "depth_000000.png";
  REQUIRE(fs::exists(depth));
  const std::string before = text_of(manifest), mesh_before = text_of(dir / "object.obj");
  const std::string out = "--out " + (dir / "out.csv").string();
  const std::pair<std::string, std::string> cases[] = {
      {"--out " + manifest.string(), "--out"},
      {out + " --summary " + manifest.string(), "--summary"},
      {out + " --summary " + (dir / "object.obj").string(), "--summary"},
      {"--out " + (dir / "seq/../object.obj").string(), "--out"},
      {out + " --summary " + (dir / "out.csv").string(), "also the file of --out"},
  };
  for (const auto& [arguments, option] : cases) {
    const auto [status, output] = track(dir, dir / "seq", arguments);
    INFO(arguments << ": " << output);
    CHECK(status == 1);
    CHECK_THAT(output, Contains(option));
    CHECK_THAT(output, Contains("names an input") || Contains("also the file of"));
  }
  CHECK(text_of(manifest) == before);
  CHECK(text_of(dir / "object.obj") == mesh_before);
  CHECK(fs::file_size(depth) > 0);
}

TEST_CASE("track: --overlay into a BOP scene's depth folder is refused: its pictures would replace the depth images",
          "[cli][outputs]") {
  const auto dir = test::write_cli_sequence("safe_overlay_bop", 2);
  const fs::path scene = bop_scene(dir);
  const std::string depth_before = text_of(scene / "depth" / "000000.png");
  const auto [status, output] =
      test::run_cli("track --mesh " + (dir / "object_mm.obj").string() + " --sequence " + scene.string() +
                        " --object 1 --resolution 80x60 --particles 20 "
                        "--init-from-gt --out " +
                        (dir / "out.csv").string() + " --overlay " + (scene / "depth").string(),
                    dir / "log.txt");
  INFO(output);
  CHECK(status == 1);
  CHECK_THAT(output, Contains("--overlay") && Contains("names an input") && Contains("000000.png"));
  CHECK(text_of(scene / "depth" / "000000.png") == depth_before);
  CHECK_FALSE(fs::exists(dir / "out.csv"));
}

TEST_CASE("a failed run leaves earlier overlay pictures as they were; a good one replaces them", "[cli][outputs]") {
  const auto dir = test::write_cli_sequence("safe_overlay", 2);
  fs::create_directories(dir / "pictures");
  const std::vector<fs::path> earlier = {dir / "out.csv", dir / "pictures" / "000000.png"};
  write_earlier(earlier);
  const auto [status, output] = track(
      dir, dir / "seq",
      "--out " + (dir / "out.csv").string() + " --overlay " + (dir / "pictures").string() + " --summary /dev/full");
  INFO(output);
  CHECK(status == 1);
  check_earlier(earlier);
  CHECK_FALSE(fs::exists(dir / "pictures" / "000001.png"));
  const auto [ok, ok_output] =
      track(dir, dir / "seq", "--out " + (dir / "out.csv").string() + " --overlay " + (dir / "pictures").string());
  INFO(ok_output);
  REQUIRE(ok == 0);
  CHECK(text_of(dir / "pictures" / "000000.png").rfind("\x89PNG", 0) == 0);
  CHECK(fs::exists(dir / "pictures" / "000001.png"));
  CHECK_FALSE(fs::exists(dir / "pictures" / "000000.png.partial"));
}

TEST_CASE("plot refuses to write over its input CSV and keeps an earlier picture when it fails", "[cli][outputs]") {
  const auto dir = test::temp_dir("safe_plot");
  const std::string csv = "frame,timestamp,ess\n000000,0,10\n000001,0.1,12\n";
  std::ofstream(dir / "run.csv") << csv;
  const auto [same, same_output] =
      test::run_cli("plot " + (dir / "run.csv").string() + " --out " + (dir / "run.csv").string(), dir / "log.txt");
  CHECK(same == 1);
  CHECK_THAT(same_output, Contains("names an input"));
  CHECK(text_of(dir / "run.csv") == csv);
  // A CSV plot cannot read: the earlier picture stays, and no partial file is left.
  write_earlier({dir / "plot.png"});
  std::ofstream(dir / "bad.csv") << "frame,timestamp,ess\n000000,0,ten\n";
  const auto [bad, bad_output] =
      test::run_cli("plot " + (dir / "bad.csv").string() + " --out " + (dir / "plot.png").string(), dir / "log.txt");
  CHECK(bad == 1);
  CHECK_THAT(bad_output, Contains("not a number"));
  check_earlier({dir / "plot.png"});
  const auto [missing, missing_output] = test::run_cli(
      "plot " + (dir / "run.csv").string() + " --out " + (dir / "no/such/p.png").string(), dir / "log.txt");
  CHECK(missing == 1);
  CHECK_THAT(missing_output, Contains("does not exist"));
}

TEST_CASE("plot draws a series per object of a several-object CSV", "[cli][outputs]") {
  const auto dir = test::temp_dir("plot_objects");
  {
    std::ofstream csv(dir / "run.csv");
    csv << "object,frame,timestamp,ess\n";
    for (int i = 0; i < 4; ++i)
      csv << "a,00000" << i << "," << 0.1 * i << ",10\n"
          << "b,00000" << i << "," << 0.1 * i << ",30\n";
  }
  const auto [status, output] =
      test::run_cli("plot " + (dir / "run.csv").string() + " --out " + (dir / "p.png").string(), dir / "log.txt");
  if (output.find("needs python3 with matplotlib") != std::string::npos) {
    std::printf("SKIPPED: no python3 with matplotlib here\n");
    return;
  }
  INFO(output);
  REQUIRE(status == 0);
  CHECK_THAT(output, Contains("4 frames, 2 objects"));
  // Object a in matplotlib's first colour (tab:blue, 31 119 180), b in its second (tab:orange, 255 127 14).
  const viz::RgbImage image = viz::RgbImage::load_png(dir / "p.png");
  auto near = [](viz::Rgb p, int r, int g, int b) {
    return std::abs(p.r - r) <= 12 && std::abs(p.g - g) <= 12 && std::abs(p.b - b) <= 12;
  };
  int first = 0, second = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      first += near(image.at(x, y), 31, 119, 180);
      second += near(image.at(x, y), 255, 127, 14);
    }
  CHECK(first > 50);
  CHECK(second > 50);
  // Objects over different frames: each over its own.
  std::ofstream(dir / "uneven.csv") << "object,frame,timestamp,ess\na,000000,0,1\nb,000000,0,2\na,000001,0.1,1\n";
  const auto [uneven, uneven_output] =
      test::run_cli("plot " + (dir / "uneven.csv").string() + " --out " + (dir / "u.png").string(), dir / "log.txt");
  CHECK(uneven == 0);
  CHECK_THAT(uneven_output, Contains("1 panel, 2 frames, 2 objects"));
}

TEST_CASE("an interrupted track (SIGINT, SIGTERM) leaves the earlier --out and no partial file", "[cli][outputs]") {
  const auto dir = test::write_cli_sequence("cli_interrupted", 40);
  for (const int signal_number : {SIGINT, SIGTERM}) {
    INFO("signal " << signal_number);
    const fs::path out = dir / "out.csv";
    write_earlier({out});
    const std::string run = "exec " + std::string(DEPTHTRACK_CLI) + " track --mesh " + (dir / "object.obj").string() +
                            " --sequence " + (dir / "seq").string() +
                            " --backend reference --resolution 160x120 --particles 3000 --init-from-gt --out " +
                            out.string() + " > " + (dir / "log.txt").string() + " 2>&1";
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      std::signal(SIGINT, SIG_DFL);  // as from a terminal: the signals are not ignored
      std::signal(SIGTERM, SIG_DFL);
      execl("/bin/sh", "sh", "-c", run.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    // Signalled once its partial CSV exists: it is tracking.
    const fs::path partial = out.string() + ".partial.partial";
    for (int i = 0; i < 1200 && !fs::exists(partial); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(25));
    CHECK(fs::exists(partial));
    kill(pid, signal_number);
    int status = 0;
    REQUIRE(waitpid(pid, &status, 0) == pid);
    INFO(text_of(dir / "log.txt"));
    // Ended by the signal, as the signal ends a program, not by finishing first.
    CHECK(WIFSIGNALED(status));
    if (WIFSIGNALED(status)) CHECK(WTERMSIG(status) == signal_number);
    check_earlier({out});
  }
}

TEST_CASE("synth replaces an earlier sequence folder only when it succeeds, and never a folder of other files",
          "[cli][outputs]") {
  const auto dir = test::temp_dir("cli_synth_staged");
  const fs::path seq = dir / "seq";
  auto synth = [&](const std::string& arguments) {
    return test::run_cli("synth --builtin --resolution 80x60 --out " + seq.string() + " " + arguments, dir / "log.txt");
  };
  {
    const auto [status, output] = synth("--seed 1 --frames 3");
    INFO(output);
    REQUIRE(status == 0);
  }
  const std::string manifest = text_of(seq / "sequence.json");
  // A run that fails after validation (its staging folder cannot be made) leaves the earlier sequence.
  std::ofstream(seq.string() + ".partial") << "in the way\n";
  {
    const auto [status, output] = synth("--seed 2 --frames 5");
    INFO(output);
    CHECK(status == 1);
    CHECK(output.find(seq.string() + ".partial") != std::string::npos);
  }
  CHECK(text_of(seq / "sequence.json") == manifest);
  CHECK(load_sequence(seq).frames.size() == 3);
  fs::remove(seq.string() + ".partial");
  // A good run replaces the whole folder: no frame of the earlier, longer sequence stays behind.
  {
    const auto [status, output] = synth("--seed 2 --frames 5");
    INFO(output);
    REQUIRE(status == 0);
    REQUIRE(synth("--seed 2 --frames 2").first == 0);
  }
  CHECK(load_sequence(seq).frames.size() == 2);
  size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(seq)) ++files;
  CHECK(files == 3);  // two depth images and sequence.json
  CHECK_FALSE(fs::exists(seq.string() + ".previous"));
  // A folder that holds something other than a sequence is refused untouched.
  const fs::path mine = dir / "mine";
  fs::create_directories(mine);
  std::ofstream(mine / "notes.txt") << "mine\n";
  {
    const auto [status, output] =
        test::run_cli("synth --builtin --frames 2 --resolution 80x60 --out " + mine.string(), dir / "log.txt");
    INFO(output);
    CHECK(status == 1);
    CHECK(output.find("not a sequence folder") != std::string::npos);
  }
  CHECK(text_of(mine / "notes.txt") == "mine\n");
  CHECK_FALSE(fs::exists(mine / "sequence.json"));
}
