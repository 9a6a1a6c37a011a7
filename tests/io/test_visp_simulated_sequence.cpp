// ViSP's simulated depth sequences (the castle) converted into depthtrack's layout: files written here
// with known pixels and poses come out exactly, every malformed file is refused by name, and the real
// castle's ground truth, drawn with its model, lands on its depth (which also checks the depth camera's
// offset from the colour camera the poses are given for).
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cstdint>
#include <depthtrack/error.hpp>
#include <depthtrack/mesh.hpp>
#include <fstream>
#include <vector>

#include "io/visp_simulated_sequence.hpp"
#include "reference/rasterizer.hpp"
#include "support.hpp"

using namespace depthtrack;
using Catch::Matchers::Contains;

namespace {

void write_depth_bin(const std::filesystem::path& path, uint32_t width, uint32_t height,
                     const std::vector<uint16_t>& values) {
  std::ofstream out(path, std::ios::binary);
  auto put32 = [&](uint32_t x) {
    for (int i = 0; i < 4; ++i) out.put(static_cast<char>((x >> (8 * i)) & 0xff));
  };
  put32(height);
  put32(width);
  for (uint16_t v : values) {
    out.put(static_cast<char>(v & 0xff));
    out.put(static_cast<char>(v >> 8));
  }
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// A two-frame sequence of 3x2 images: frame 1's pose turns 90 degrees about x, frame 2's is a translation.
std::filesystem::path write_small_sequence(const std::string& name) {
  const auto dir = test::temp_dir(name);
  for (const char* sub : {"Depth", "CameraPose", "Config"}) std::filesystem::create_directories(dir / sub);
  write_depth_bin(dir / "Depth" / "Depth_0001.bin", 3, 2, {0, 1, 32768, 65535, 16384, 3});
  write_depth_bin(dir / "Depth" / "Depth_0002.bin", 3, 2, {32768, 32768, 32768, 0, 0, 0});
  write_text(dir / "CameraPose" / "Camera_001.txt", "1 0 0 0.1\n0 0 -1 0.2\n0 1 0 0.7\n0 0 0 1\n");
  write_text(dir / "CameraPose" / "Camera_002.txt", "1 0 0 0\n0 1 0 0\n0 0 1 1.5\n0 0 0 1\n");
  write_text(dir / "Config" / "box_depth.xml",
             "<?xml version=\"1.0\"?>\n<conf>\n  <camera>\n    <px>100</px>\n    <py> 110 </py>\n"
             "    <u0>1.5</u0>\n    <v0>0.5</v0>\n  </camera>\n</conf>\n");
  return dir;
}

io::VispSimulatedImport castle_offset() {
  io::VispSimulatedImport options;
  options.depth_from_colour = Pose(Eigen::Vector3d(-0.05, 0, 0), Eigen::Quaterniond::Identity());
  return options;
}

}  // namespace

TEST_CASE("A ViSP simulated sequence converts into depthtrack's layout with its pixels, poses and intrinsics",
          "[io][visp]") {
  const auto in = write_small_sequence("visp_small_in");
  const auto out = test::temp_dir("visp_small_out");
  io::import_visp_simulated_sequence(in, out, castle_offset());

  const Sequence s = load_sequence(out);
  REQUIRE(s.frames.size() == 2);
  CHECK(s.frames[0].name == "000001");
  CHECK(s.frames[1].name == "000002");
  CHECK(s.frames[1].timestamp == Approx(1.0 / 30.0));
  CHECK(s.camera.width == 3);
  CHECK(s.camera.height == 2);
  CHECK(s.camera.fx == 100.0);
  CHECK(s.camera.fy == 110.0);
  // The file's u0 v0 (1.5, 0.5) at half-integer pixel centres: depthtrack's pixel u is at u.
  CHECK(s.camera.cx == 1.0);
  CHECK(s.camera.cy == 0.0);

  // metres = value / 32768, exactly (a power of two); 0 is no measurement.
  const DepthImage d = s.load_depth(0);
  CHECK(!DepthImage::is_valid(d.at(0, 0)));
  CHECK(d.at(1, 0) == 1.0f / 32768.0f);
  CHECK(d.at(2, 0) == 1.0f);
  CHECK(d.at(0, 1) == 65535.0f / 32768.0f);
  CHECK(d.at(1, 1) == 0.5f);
  CHECK(d.at(2, 1) == 3.0f / 32768.0f);

  // The depth camera's pose: the colour camera's moved by (-0.05, 0, 0), the rotation unchanged.
  const Pose gt = *s.frames[0].ground_truth;
  CHECK(gt.translation.x() == Approx(0.05).margin(1e-12));
  CHECK(gt.translation.y() == Approx(0.2).margin(1e-12));
  CHECK(gt.translation.z() == Approx(0.7).margin(1e-12));
  const Eigen::Vector3d y_turned = gt.rotation * Eigen::Vector3d::UnitY();  // 90 degrees about x: y -> z
  CHECK(y_turned.z() == Approx(1.0).margin(1e-12));
  CHECK(s.frames[1].ground_truth->translation.isApprox(Eigen::Vector3d(-0.05, 0, 1.5)));
}

TEST_CASE("A malformed ViSP simulated sequence is refused, naming the file and the problem", "[io][visp]") {
  const auto out = test::temp_dir("visp_bad_out");
  auto refused = [&](const std::filesystem::path& in, const std::string& words) {
    CHECK_THROWS_WITH(io::import_visp_simulated_sequence(in, out, castle_offset()), Contains(words));
  };
  SECTION("a depth file shorter than its header says") {
    const auto in = write_small_sequence("visp_bad_short");
    write_depth_bin(in / "Depth" / "Depth_0002.bin", 3, 2, {1, 2, 3});
    refused(in, "Depth_0002.bin' holds 14 bytes; a 3x2 image needs 20");
  }
  SECTION("an impossible size in the header") {
    const auto in = write_small_sequence("visp_bad_header");
    write_depth_bin(in / "Depth" / "Depth_0001.bin", 0, 2, {});
    refused(in, "impossible size 0x2");
    write_depth_bin(in / "Depth" / "Depth_0001.bin", 100000, 100000, {});
    refused(in, "impossible size 100000x100000");
  }
  SECTION("a frame of another size than the first") {
    const auto in = write_small_sequence("visp_bad_size");
    write_depth_bin(in / "Depth" / "Depth_0002.bin", 2, 3, {1, 2, 3, 4, 5, 6});
    refused(in, "is 2x3, not 3x2");
  }
  SECTION("a pose that is not 16 numbers, not rigid, or missing") {
    const auto in = write_small_sequence("visp_bad_pose");
    write_text(in / "CameraPose" / "Camera_002.txt", "1 0 0 0\n0 1 0 0\n0 0 1 1.5\n");
    refused(in, "Camera_002.txt' must hold a 4x4 matrix of 16 finite numbers");
    write_text(in / "CameraPose" / "Camera_002.txt", "1 0 0 0\n0 1 0 0\n0 0 1 nan\n0 0 0 1\n");
    refused(in, "16 finite numbers");
    write_text(in / "CameraPose" / "Camera_002.txt", "2 0 0 0\n0 1 0 0\n0 0 1 1\n0 0 0 1\n");
    refused(in, "Camera_002.txt'");
    write_text(in / "CameraPose" / "Camera_002.txt", "1 0 0 0\n0 1 0 0\n0 0 1 1\n0 0 1 1\n");
    refused(in, "the last row must be 0 0 0 1");
    std::filesystem::remove(in / "CameraPose" / "Camera_002.txt");
    refused(in, "Depth_0002.bin' has no pose");
  }
  SECTION("intrinsics missing or impossible") {
    const auto in = write_small_sequence("visp_bad_camera");
    write_text(in / "Config" / "box_depth.xml", "<conf><camera><px>100</px><py>110</py><u0>1</u0></camera></conf>");
    refused(in, "<camera> has no number in <v0>");
    write_text(in / "Config" / "box_depth.xml",
               "<conf><camera><px>-100</px><py>110</py><u0>1</u0><v0>1</v0></camera></conf>");
    refused(in, "box_depth.xml'");
    std::filesystem::remove(in / "Config" / "box_depth.xml");
    refused(in, "must hold exactly one *_depth.xml");
  }
  SECTION("no depth files at all") {
    const auto in = write_small_sequence("visp_bad_empty");
    std::filesystem::remove_all(in / "Depth");
    refused(in, "Depth' is not a folder");
  }
}

TEST_CASE("A malformed ViSP sequence leaves an earlier import in the same folder whole", "[io][visp]") {
  const auto good = write_small_sequence("visp_keep_good");
  const auto out = test::temp_dir("visp_keep_out");
  io::import_visp_simulated_sequence(good, out, castle_offset());
  // The second frame's depth is short: found only after the first frame's would have been written.
  const auto bad = write_small_sequence("visp_keep_bad");
  write_depth_bin(bad / "Depth" / "Depth_0001.bin", 3, 2, {7, 7, 7, 7, 7, 7});
  write_depth_bin(bad / "Depth" / "Depth_0002.bin", 3, 2, {1, 2, 3});
  CHECK_THROWS_WITH(io::import_visp_simulated_sequence(bad, out, castle_offset()), Contains("Depth_0002.bin"));
  const Sequence kept = load_sequence(out);
  REQUIRE(kept.frames.size() == 2);
  CHECK(kept.load_depth(0).at(2, 0) == 1.0f);  // the good import's first frame, not the 7s
  CHECK(kept.load_depth(1).at(0, 0) == 1.0f);
}

TEST_CASE("The castle's ground truth, drawn with its model, lies on its depth", "[io][visp][data]") {
  const auto castle = test::shared_data("sequences/visp-castle-simu");
  if (!castle) return;
  const auto out = test::temp_dir("visp_castle");
  const Sequence s = io::import_visp_simulated_sequence(*castle, out, castle_offset());
  REQUIRE(s.frames.size() == 40);
  CHECK(s.camera.width == 640);
  CHECK(s.camera.fx == 700.0);

  const Mesh model = Mesh::load(*castle / "Models" / "DERIVED_chateau_plus_cube_triangulated.obj");
  const reference::Rasterizer rasterizer(model, s.camera, 0.01, 2.0);
  std::vector<float> drawn(static_cast<size_t>(s.camera.pixel_count()));
  // At a pose: the median |drawn - measured| over the pixels both have (metres), and the share of the
  // drawn pixels where the sensor sees nothing (background).
  auto agreement_in = [&](const Sequence& seq, const reference::Rasterizer& drawer, size_t frame, const Pose& pose) {
    drawer.render(pose, drawn);
    const DepthImage depth = seq.load_depth(frame);
    std::vector<double> residuals;
    size_t covered = 0;
    for (int v = 0; v < s.camera.height; ++v)
      for (int u = 0; u < s.camera.width; ++u) {
        const float z = drawn[static_cast<size_t>(v) * s.camera.width + u];
        if (!(z > 0)) continue;
        ++covered;
        if (DepthImage::is_valid(depth.at(u, v))) residuals.push_back(std::abs(z - depth.at(u, v)));
      }
    REQUIRE(residuals.size() > 10000);
    std::nth_element(residuals.begin(), residuals.begin() + residuals.size() / 2, residuals.end());
    return std::pair{residuals[residuals.size() / 2], 1.0 - static_cast<double>(residuals.size()) / covered};
  };
  auto agreement = [&](size_t frame, const Pose& pose) { return agreement_in(s, rasterizer, frame, pose); };
  // The same files read with integer pixel centres (the file's u0 v0 as they are).
  io::VispSimulatedImport integer_centres = castle_offset();
  integer_centres.pixel_centre = 0;
  const Sequence shifted =
      io::import_visp_simulated_sequence(*castle, test::temp_dir("visp_castle_integer"), integer_centres);
  CHECK(shifted.camera.cx == s.camera.cx + 0.5);
  const reference::Rasterizer shifted_rasterizer(model, shifted.camera, 0.01, 2.0);
  for (size_t frame : {size_t{0}, size_t{20}, size_t{39}}) {
    INFO("frame " << s.frames[frame].name);
    const auto [residual, off_object] = agreement(frame, *s.frames[frame].ground_truth);
    CHECK(residual < 0.001);
    CHECK(off_object < 0.01);
    // Half-integer pixel centres: at integer ones the drawn outline lies half a pixel up and left of
    // the measured one, over more background.
    CHECK(agreement_in(shifted, shifted_rasterizer, frame, *s.frames[frame].ground_truth).second > off_object);
    // The colour camera's pose itself (the offset undone): the flat faces still meet the depth, but the
    // model is drawn 5 cm to the side, over background.
    const Pose colour = castle_offset().depth_from_colour.inverse() * *s.frames[frame].ground_truth;
    CHECK(agreement(frame, colour).second > 0.2);
  }
}
