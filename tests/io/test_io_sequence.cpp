// Sequences on disk: depthtrack's manifest round trip, the YCB-Video clip layout, and bad folders.
#include <algorithm>
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/sequence.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support.hpp"

using namespace depthtrack;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A small depth image whose pixel values depend on a seed, saved in 0.1 mm units.
DepthImage test_depth(int width, int height, float seed) {
  std::vector<float> metres(static_cast<size_t>(width * height));
  for (size_t i = 0; i < metres.size(); ++i) metres[i] = 0.5f + seed + 0.001f * static_cast<float>(i);
  metres[3] = 0.0f;  // one missing pixel
  return DepthImage::from_metres(width, height, metres);
}

// A depthtrack sequence of three 8x6 frames in dir, optionally with ground truth.
Sequence make_sequence(const fs::path& dir, bool with_ground_truth) {
  Sequence s;
  s.format = "depthtrack";
  s.object = with_ground_truth ? "box" : "";
  s.camera = Camera::make(8, 6, 10.5, 11.0, 3.5, 2.5);
  s.metres_per_unit = 1e-4;
  for (int i = 0; i < 3; ++i) {
    SequenceFrame f;
    f.name = "00000" + std::to_string(i);
    f.timestamp = 0.1 * i + 1.0 / 3.0;
    f.depth_path = dir / (f.name + ".png");
    test_depth(8, 6, 0.1f * static_cast<float>(i)).save_png(f.depth_path, s.metres_per_unit);
    if (with_ground_truth)
      f.ground_truth = Pose({0.01 * i, -0.02, 0.8}, rotation_exp(Eigen::Vector3d(0.1, -0.2 * i, 0.3)));
    s.frames.push_back(f);
  }
  return s;
}

// A YCB-Video style gt.json over 8x6 depth PNGs: frames 1, 2 and 4 (frame 3 dropped); two objects,
// the brick absent from frame 2.
fs::path make_ycb_clip(const std::string& name) {
  const auto dir = test::temp_dir(name);
  nlohmann::json frames = nlohmann::json::array();
  for (int number : {1, 2, 4}) {
    char id[8];
    std::snprintf(id, sizeof id, "%06d", number);
    const std::string depth = std::string(id) + "-depth.png";
    test_depth(8, 6, 0.0f).save_png(dir / depth, 1e-4);
    nlohmann::json objects = nlohmann::json::array();
    const auto transform = [&](double x) {
      return nlohmann::json{{1, 0, 0, x}, {0, 1, 0, 0.1 * number}, {0, 0, 1, 0.7}, {0, 0, 0, 1}};
    };
    objects.push_back({{"cls_index", 14}, {"name", "025_mug"}, {"T_cam_obj", transform(0.05)}});
    if (number != 2)
      objects.push_back({{"cls_index", 21}, {"name", "061_foam_brick"}, {"T_cam_obj", transform(-0.05)}});
    frames.push_back({{"frame", id},
                      {"depth", depth},
                      {"factor_depth", 10000.0},
                      // A focal length for 8x6 pixels (a 640x480 camera's 500 would be a 1-degree lens).
                      {"K", {{5.0, 0.0, 3.5}, {0.0, 5.01, 2.5}, {0.0, 0.0, 1.0}}},
                      {"objects", objects}});
  }
  write_text(dir / "gt.json", nlohmann::json{{"frames", frames}}.dump(1));
  return dir;
}

void require_same_pose(const Pose& a, const Pose& b) {
  REQUIRE(translation_error(a, b) < 1e-12);
  REQUIRE(rotation_error(a, b) < 1e-9);
}

}  // namespace

TEST_CASE("write_sequence_manifest and load_sequence round-trip ground truth", "[io]") {
  const auto dir = test::temp_dir("io_seq_roundtrip");
  const Sequence written = make_sequence(dir, true);
  write_sequence_manifest(dir, written);
  const Sequence read = load_sequence(dir);
  REQUIRE(read.format == "depthtrack");
  REQUIRE(read.object == "box");
  REQUIRE(read.camera.width == 8);
  REQUIRE(read.camera.height == 6);
  REQUIRE(read.camera.fx == 10.5);
  REQUIRE(read.camera.fy == 11.0);
  REQUIRE(read.camera.cx == 3.5);
  REQUIRE(read.camera.cy == 2.5);
  REQUIRE(read.metres_per_unit == 1e-4);
  REQUIRE(read.frames.size() == 3);
  for (size_t i = 0; i < 3; ++i) {
    REQUIRE(read.frames[i].name == written.frames[i].name);
    REQUIRE(read.frames[i].timestamp == written.frames[i].timestamp);  // JSON keeps doubles exactly
    REQUIRE(read.frames[i].depth_path == written.frames[i].depth_path);
    REQUIRE(read.frames[i].ground_truth.has_value());
    require_same_pose(*read.frames[i].ground_truth, *written.frames[i].ground_truth);
  }
  const DepthImage depth = read.load_depth(2);
  const DepthImage expected = test_depth(8, 6, 0.2f);
  REQUIRE(depth.valid_count() == 47);
  for (size_t i = 0; i < expected.data().size(); ++i)
    if (DepthImage::is_valid(expected.data()[i])) REQUIRE(depth.data()[i] == Approx(expected.data()[i]).margin(0.5e-4));
}

TEST_CASE("the sequence manifest has the documented fields, 2-space indented", "[io]") {
  const auto dir = test::temp_dir("io_seq_manifest");
  const Sequence written = make_sequence(dir, true);
  write_sequence_manifest(dir, written);
  const std::string text = read_text(dir / "sequence.json");
  REQUIRE(text.rfind("{\n  \"format\": \"depthtrack-sequence\"", 0) == 0);
  const auto json = nlohmann::json::parse(text);
  REQUIRE(json["version"] == 1);
  REQUIRE(json["camera"]["width"] == 8);
  REQUIRE(json["camera"]["fx"] == 10.5);
  REQUIRE(json["metres_per_unit"] == 1e-4);
  REQUIRE(json["object"] == "box");
  const auto& frame = json["frames"][1];
  REQUIRE(frame["name"] == "000001");
  REQUIRE(frame["depth"] == "000001.png");  // relative to the folder
  REQUIRE(frame["T_cam_obj"].size() == 16);
  // Row-major: the translation is the last column.
  const Eigen::Vector3d t = written.frames[1].ground_truth->translation;
  REQUIRE(frame["T_cam_obj"][3].get<double>() == t.x());
  REQUIRE(frame["T_cam_obj"][7].get<double>() == t.y());
  REQUIRE(frame["T_cam_obj"][11].get<double>() == t.z());
  REQUIRE(frame["T_cam_obj"][15].get<double>() == 1.0);
  const Eigen::Matrix3d r = written.frames[1].ground_truth->rotation.toRotationMatrix();
  REQUIRE(frame["T_cam_obj"][1].get<double>() == Approx(r(0, 1)).margin(1e-15));
  REQUIRE(frame["T_cam_obj"][4].get<double>() == Approx(r(1, 0)).margin(1e-15));
}

TEST_CASE("a sequence without ground truth round-trips without it", "[io]") {
  const auto dir = test::temp_dir("io_seq_no_gt");
  write_sequence_manifest(dir, make_sequence(dir, false));
  REQUIRE(read_text(dir / "sequence.json").find("T_cam_obj") == std::string::npos);
  const Sequence read = load_sequence(dir);
  REQUIRE(read.object.empty());
  REQUIRE(read.frames.size() == 3);
  for (const auto& f : read.frames) REQUIRE_FALSE(f.ground_truth.has_value());
}

TEST_CASE("load_sequence reads the YCB-Video clip ycbv-0000 for the mug", "[io]") {
  const auto dir = test::shared_data("sequences/ycbv-0000");
  if (!dir) return;
  const Sequence s = load_sequence(*dir, "mug");
  REQUIRE(s.format == "ycb-video");
  REQUIRE(s.object == "025_mug");
  REQUIRE(s.frames.size() == 20);
  REQUIRE(s.camera.width == 640);
  REQUIRE(s.camera.height == 480);
  REQUIRE(s.camera.fx == 1066.778);
  REQUIRE(s.camera.fy == 1067.487);
  REQUIRE(s.camera.cx == 312.9869);
  REQUIRE(s.camera.cy == 241.3109);
  REQUIRE(s.metres_per_unit == Approx(1e-4).epsilon(1e-12));
  REQUIRE(s.frames[0].name == "000001");
  REQUIRE(s.frames[0].timestamp == 0.0);
  REQUIRE(s.frames[9].timestamp == Approx(9.0 / 30.0));
  REQUIRE(s.frames[19].name == "000020");
  REQUIRE(s.frames[19].timestamp == Approx(19.0 / 30.0));
  REQUIRE(s.frames[0].ground_truth.has_value());
  const Eigen::Vector3d t = s.frames[0].ground_truth->translation;
  REQUIRE(t.x() == 0.05854422693862422);
  REQUIRE(t.y() == -0.02146404567317504);
  REQUIRE(t.z() == 0.6168090183158172);

  const DepthImage depth = s.load_depth(0);
  REQUIRE(depth.width() == 640);
  REQUIRE(depth.height() == 480);
  REQUIRE(depth.valid_count() > 640 * 480 / 2);  // a real Xtion frame: most pixels have a depth
  std::vector<float> valid;
  for (float z : depth.data())
    if (DepthImage::is_valid(z)) valid.push_back(z);
  std::nth_element(valid.begin(), valid.begin() + static_cast<std::ptrdiff_t>(valid.size() / 2), valid.end());
  const float median = valid[valid.size() / 2];
  REQUIRE(median > 0.4f);
  REQUIRE(median < 1.5f);
}

TEST_CASE("a YCB-Video clip: timestamps from frame numbers, size from the PNG, absent objects", "[io]") {
  const auto dir = make_ycb_clip("io_seq_ycb_small");
  const Sequence s = load_sequence(dir, "brick");  // a substring picks 061_foam_brick
  REQUIRE(s.object == "061_foam_brick");
  REQUIRE(s.camera.width == 8);
  REQUIRE(s.camera.height == 6);
  REQUIRE(s.camera.fy == 5.01);
  REQUIRE(s.frames.size() == 3);
  REQUIRE(s.frames[1].timestamp == Approx(1.0 / 30.0));
  REQUIRE(s.frames[2].timestamp == Approx(3.0 / 30.0));  // frame 3 was dropped
  REQUIRE(s.frames[0].ground_truth.has_value());
  REQUIRE_FALSE(s.frames[1].ground_truth.has_value());  // the brick is not in frame 2
  REQUIRE(s.frames[2].ground_truth->translation.x() == -0.05);
  REQUIRE(s.frames[2].ground_truth->translation.y() == Approx(0.4));
  REQUIRE(load_sequence(dir, "025_mug").frames[1].ground_truth.has_value());
  REQUIRE(load_sequence(dir, "025").object == "025_mug");
}

TEST_CASE("a YCB-Video clip with several objects needs one chosen", "[io]") {
  const auto dir = make_ycb_clip("io_seq_ycb_choose");
  REQUIRE_THROWS_AS(load_sequence(dir), InputError);
  REQUIRE_THROWS_WITH(load_sequence(dir), Contains("025_mug") && Contains("061_foam_brick"));
  // "0" is in both names: ambiguous.
  REQUIRE_THROWS_WITH(load_sequence(dir, "0"), Contains("ambiguous"));
}

// ---- Bad sequences ----

TEST_CASE("an unknown YCB-Video object lists the objects present", "[io]") {
  const auto dir = make_ycb_clip("io_seq_ycb_unknown");
  REQUIRE_THROWS_AS(load_sequence(dir, "banana"), InputError);
  REQUIRE_THROWS_WITH(load_sequence(dir, "banana"),
                      Contains("banana") && Contains("025_mug") && Contains("061_foam_brick") && Contains("gt.json"));
}

TEST_CASE("load_depth of an image whose size differs from the camera names both sizes", "[io]") {
  const auto dir = test::temp_dir("io_seq_size");
  Sequence s = make_sequence(dir, false);
  s.camera = Camera::make(640, 480, 525, 525, 319.5, 239.5);
  write_sequence_manifest(dir, s);
  const Sequence read = load_sequence(dir);
  REQUIRE_THROWS_AS(read.load_depth(0), InputError);
  REQUIRE_THROWS_WITH(read.load_depth(0), Contains("000000.png") && Contains("is 8x6 but the camera is 640x480"));
}

TEST_CASE("load_depth of a frame index out of range", "[io]") {
  const auto dir = test::temp_dir("io_seq_index");
  write_sequence_manifest(dir, make_sequence(dir, false));
  REQUIRE_THROWS_WITH(load_sequence(dir).load_depth(3), Contains("3") && Contains("out of range"));
}

TEST_CASE("load_sequence of a missing folder", "[io]") {
  const auto dir = test::temp_dir("io_seq_missing") / "not-there";
  REQUIRE_THROWS_AS(load_sequence(dir), InputError);
  REQUIRE_THROWS_WITH(load_sequence(dir), Contains("not-there") && Contains("does not exist"));
}

TEST_CASE("load_sequence of a folder with neither manifest", "[io]") {
  const auto dir = test::temp_dir("io_seq_neither");
  REQUIRE_THROWS_WITH(load_sequence(dir), Contains("sequence.json") && Contains("gt.json"));
}

TEST_CASE("load_sequence of a corrupt manifest names the file", "[io]") {
  const auto dir = test::temp_dir("io_seq_corrupt");
  write_text(dir / "sequence.json", "{\"format\": \"depthtrack-sequence\", \"version\": 1, \"camera\": {");
  REQUIRE_THROWS_AS(load_sequence(dir), InputError);
  REQUIRE_THROWS_WITH(load_sequence(dir), Contains("sequence.json") && Contains("not valid JSON"));
}

TEST_CASE("load_sequence of a manifest with a missing or wrong field names file and field", "[io]") {
  const auto dir = test::temp_dir("io_seq_field");
  write_sequence_manifest(dir, make_sequence(dir, true));
  auto json = nlohmann::json::parse(read_text(dir / "sequence.json"));
  auto broken = json;
  broken["camera"].erase("fx");
  write_text(dir / "sequence.json", broken.dump());
  REQUIRE_THROWS_WITH(load_sequence(dir), Contains("sequence.json") && Contains("camera.fx") && Contains("missing"));

  broken = json;
  broken["frames"][1]["timestamp"] = "soon";
  write_text(dir / "sequence.json", broken.dump());
  REQUIRE_THROWS_WITH(load_sequence(dir), Contains("frames[1].timestamp") && Contains("number"));

  broken = json;
  broken["frames"][2]["T_cam_obj"][0] = 5.0;  // not a rotation any more
  write_text(dir / "sequence.json", broken.dump());
  REQUIRE_THROWS_WITH(load_sequence(dir), Contains("frames[2].T_cam_obj") && Contains("rotation"));

  broken = json;
  broken["format"] = "something-else";
  write_text(dir / "sequence.json", broken.dump());
  REQUIRE_THROWS_WITH(load_sequence(dir), Contains("format"));
}

TEST_CASE("load_sequence of a gt.json missing a field names file and field", "[io]") {
  const auto dir = make_ycb_clip("io_seq_ycb_field");
  auto json = nlohmann::json::parse(read_text(dir / "gt.json"));
  json["frames"][1].erase("K");
  write_text(dir / "gt.json", json.dump());
  REQUIRE_THROWS_WITH(load_sequence(dir, "mug"), Contains("gt.json") && Contains("frames[1].K") && Contains("missing"));
}
