// FrameSource: the raw depth stream's pixels, times and refusals, frame ranges, and a source of the test's
// own registered as a kind and tracked as a folder is.
#include <algorithm>
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <depthtrack/frame_source.hpp>
#include <depthtrack/synth.hpp>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "same_estimate.hpp"
#include "support.hpp"

using namespace depthtrack;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

// Little-endian bytes composed by hand, so that the test does not rely on the host's order.
void put_f32(std::string& out, float value) {
  const auto bits = std::bit_cast<uint32_t>(value);
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((bits >> (8 * i)) & 0xff));
}
void put_u16(std::string& out, uint16_t value) {
  out.push_back(static_cast<char>(value & 0xff));
  out.push_back(static_cast<char>(value >> 8));
}

fs::path write_bytes(const std::string& name, const std::string& bytes) {
  const fs::path path = test::temp_dir("frame_source_" + name) / "stream.raw";
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

const std::string kHeader = "depthtrack-raw-depth 1 2 2 100 110 0.5 0.5\n";

// A 2x2 stream: an f32 frame, then a u16 one in millimetres.
std::string two_frames() {
  std::string s = kHeader + "0.25 f32\n";
  for (float z : {0.5f, std::numeric_limits<float>::quiet_NaN(), 0.0f, 1.25f}) put_f32(s, z);
  s += "0.5 u16 0.001\n";
  for (uint16_t u : {1000, 0, 2, 65535}) put_u16(s, u);
  return s;
}

std::string error_of(const std::string& bytes, const std::string& name) {
  try {
    const auto source = open_frame_source("raw:" + write_bytes(name, bytes).string());
    while (source->next()) {
    }
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// Frames held in memory: what a camera driver's source looks like, registered below as kind "memory".
class MemorySource final : public FrameSource {
 public:
  MemorySource(Camera camera, std::vector<Frame> frames) : camera_(camera), frames_(std::move(frames)) {}
  const Camera& camera() const override { return camera_; }
  std::optional<Frame> next() override {
    if (next_ >= frames_.size()) return std::nullopt;
    return frames_[next_++];
  }

 private:
  Camera camera_;
  std::vector<Frame> frames_;
  size_t next_ = 0;
};

// The synthetic sequence the "memory" kind serves, read from its folder.
const Sequence& memory_sequence() {
  static const Sequence sequence = [] {
    const auto dir = test::temp_dir("frame_source_memory");
    SynthConfig c;
    c.camera = Camera::make(160, 120, 131.25, 131.25, 79.875, 59.875);
    c.frames = 5;
    write_synthetic_sequence(dir, builtin_demo_mesh(), c);
    return load_sequence(dir);
  }();
  return sequence;
}

std::unique_ptr<FrameSource> open_memory(const std::string& location, const FrameSourceOptions&) {
  const Sequence& s = memory_sequence();
  std::vector<Frame> frames;
  for (size_t i = 0; i < s.frames.size(); ++i)
    frames.push_back({s.frames[i].name, s.frames[i].timestamp, s.load_depth(i), s.frames[i].ground_truth, {}});
  if (location == "reversed") std::reverse(frames.begin(), frames.end());
  return std::make_unique<MemorySource>(s.camera, std::move(frames));
}

void register_memory_kind() {
  static const bool registered = [] {
    register_frame_source("memory", "the test's synthetic frames held in memory", open_memory);
    return true;
  }();
  (void)registered;
}

}  // namespace

TEST_CASE("The raw depth stream gives its camera, pixels, names and times, then ends", "[io][source]") {
  const auto source = open_frame_source("raw:" + write_bytes("two", two_frames()).string());
  const Camera& c = source->camera();
  CHECK(c.width == 2);
  CHECK(c.height == 2);
  CHECK(c.fx == 100.0);
  CHECK(c.fy == 110.0);
  CHECK(c.cx == 0.5);
  CHECK(c.cy == 0.5);
  CHECK_FALSE(source->size().has_value());

  const auto first = source->next();
  REQUIRE(first);
  CHECK(first->name == "000000");
  CHECK(first->timestamp == 0.25);
  CHECK(first->depth.at(0, 0) == 0.5f);
  CHECK_FALSE(DepthImage::is_valid(first->depth.at(1, 0)));
  CHECK_FALSE(DepthImage::is_valid(first->depth.at(0, 1)));
  CHECK(first->depth.at(1, 1) == 1.25f);
  CHECK_FALSE(first->ground_truth);

  const auto second = source->next();
  REQUIRE(second);
  CHECK(second->name == "000001");
  CHECK(second->timestamp == 0.5);
  CHECK(second->depth.at(0, 0) == Approx(1.0));
  CHECK_FALSE(DepthImage::is_valid(second->depth.at(1, 0)));
  CHECK(second->depth.at(0, 1) == Approx(0.002));
  CHECK(second->depth.at(1, 1) == Approx(65.535));
  CHECK_FALSE(source->next());
}

TEST_CASE("The raw depth stream refuses malformed input by what is wrong", "[io][source][errors]") {
  const std::string frames = two_frames();
  const std::string body = frames.substr(kHeader.size());
  CHECK_THAT(error_of("", "empty"), Contains("is empty"));
  CHECK_THAT(error_of("P5 2 2\n" + body, "magic"), Contains("is not a raw depth stream"));
  CHECK_THAT(error_of("depthtrack-raw-depth 2 2 2 100 110 0.5 0.5\n" + body, "version"),
             Contains("is version 2; this depthtrack reads version 1"));
  CHECK_THAT(error_of("depthtrack-raw-depth 1 0 2 100 110 0.5 0.5\n", "size"), Contains("image size 0x2"));
  CHECK_THAT(error_of("depthtrack-raw-depth 1 2 2 100\n", "short header"), Contains("is not 'depthtrack-raw-depth 1"));
  CHECK_THAT(error_of(frames.substr(0, frames.size() - 3), "truncated"),
             Contains("frame 000001: the stream ends after 5 of the frame's 8 bytes"));
  std::string backwards = frames;
  backwards.replace(backwards.find("0.5 u16"), 3, "0.2");
  CHECK_THAT(error_of(backwards, "backwards"), Contains("frame 000001: timestamp 0.200000 s is not later"));
  std::string type = frames;
  type.replace(type.find("u16"), 3, "u32");
  CHECK_THAT(error_of(type, "type"), Contains("pixel type 'u32' is neither f32"));
  std::string negative = kHeader + "0 f32\n";
  for (float z : {0.5f, -1.0f, 0.5f, 0.5f}) put_f32(negative, z);
  CHECK_THAT(error_of(negative, "negative"), Contains("frame 000000:"));
  CHECK_THAT(error_of(kHeader + "1e11 f32\n", "far time"), Contains("outside the sane range"));
  CHECK_THAT(error_of(kHeader + "0.1 f32", "unfinished line"), Contains("ends inside a line"));
  CHECK_THROWS_WITH(open_frame_source("raw:" + (test::temp_dir("frame_source_none") / "absent").string()),
                    Contains("cannot open raw depth stream"));
  CHECK_THROWS_WITH(open_frame_source("raw:-", {"025_mug"}), Contains("carries no ground truth"));
}

TEST_CASE("Frame ranges parse A:B, A: and :B and refuse the rest", "[source]") {
  const FrameRange middle = parse_frame_range("2:5");
  CHECK(middle.first == 2);
  CHECK(middle.end == 5u);
  CHECK(parse_frame_range("3:").first == 3);
  CHECK_FALSE(parse_frame_range("3:").end);
  CHECK(parse_frame_range(":4").first == 0);
  CHECK(parse_frame_range(":4").end == 4u);
  for (const auto& [text, words] :
       std::vector<std::pair<std::string, std::string>>{{"5:2", "the range is empty"},
                                                        {"3:3", "the range is empty"},
                                                        {"a:4", "'a' is not a whole number"},
                                                        {"-1:4", "'-1' is not a whole number"},
                                                        {"2", "is not A:B"},
                                                        {"1:2:3", "is not A:B"},
                                                        {":", "names neither end"}})
    CHECK_THROWS_WITH(parse_frame_range(text), Contains(words) && Contains("--frames '" + text + "'"));

  const Sequence& s = memory_sequence();
  const Sequence cut = frames_in(s, parse_frame_range("1:3"));
  REQUIRE(cut.frames.size() == 2);
  CHECK(cut.frames[0].name == s.frames[1].name);
  CHECK(cut.frames[1].name == s.frames[2].name);
  CHECK_THROWS_WITH(frames_in(s, parse_frame_range("2:6")), Contains("reaches past the sequence's 5 frames"));
  CHECK_THROWS_WITH(frames_in(s, parse_frame_range("5:")), Contains("reaches past"));
}

TEST_CASE("A registered kind opens through open_frame_source, and ranges cut any source", "[source]") {
  register_memory_kind();
  const auto kinds = frame_source_kinds();
  REQUIRE(kinds.size() >= 3);
  CHECK(kinds[0].first == "folder");
  CHECK(kinds[1].first == "raw");
  CHECK(std::any_of(kinds.begin(), kinds.end(), [](const auto& k) { return k.first == "memory"; }));
  CHECK_THROWS_WITH(register_frame_source("memory", "again", open_memory), Contains("registered already"));
  CHECK_THROWS_WITH(register_frame_source("Bad:Name", "", open_memory), Contains("must be lower-case"));
  CHECK_THROWS_WITH(open_frame_source("camera:0"), Contains("unknown kind 'camera'") && Contains("memory"));

  const auto reversed = open_frame_source("memory:reversed");
  CHECK(reversed->next()->name == memory_sequence().frames.back().name);

  const auto cut = frames_in(open_frame_source("memory:"), parse_frame_range("1:3"));
  CHECK(cut->next()->name == memory_sequence().frames[1].name);
  CHECK(cut->next()->name == memory_sequence().frames[2].name);
  CHECK_FALSE(cut->next());
  const auto past = frames_in(open_frame_source("memory:"), parse_frame_range("3:9"));
  CHECK(past->next());
  CHECK(past->next());
  CHECK_THROWS_WITH(past->next(), Contains("ended after 5 frames, before frame 8"));
  const auto late = frames_in(open_frame_source("memory:"), parse_frame_range("7:"));
  CHECK_THROWS_WITH(late->next(), Contains("before frame 7 where the range starts"));
}

TEST_CASE("Tracking a source of one's own gives the estimates of the same frames read from their folder",
          "[source][track]") {
  register_memory_kind();
  const Sequence& s = memory_sequence();
  TrackerConfig config;
  config.particles = 100;
  const Mesh mesh = builtin_demo_mesh();
  const Pose start = *s.frames.front().ground_truth;
  const InitialSpread spread{0.01, 0.05};
  const auto from_folder = track_sequence(s, mesh, config, start, spread);
  const auto source = open_frame_source("memory:");
  const auto from_memory = track_source(*source, mesh, config, start, spread);
  REQUIRE(from_memory.size() == from_folder.size());
  for (size_t i = 0; i < from_folder.size(); ++i) {
    INFO("frame " << i);
    CHECK(from_memory[i].name == from_folder[i].name);
    CHECK(from_memory[i].timestamp == from_folder[i].timestamp);
    test::require_same_estimate(from_memory[i].estimate, from_folder[i].estimate);
    CHECK(from_memory[i].translation_error == from_folder[i].translation_error);
    CHECK(from_memory[i].translation_error < 0.01);  // and tracked: within 1 cm of the truth
  }
}
