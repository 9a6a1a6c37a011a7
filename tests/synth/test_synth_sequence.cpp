// write_synthetic_sequence and the depthtrack synth command, read back through load_sequence.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <depthtrack/sequence.hpp>
#include <depthtrack/synth.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support.hpp"

using namespace depthtrack;

namespace {
SynthConfig small_config() {
  SynthConfig c;
  c.camera = Camera::make(160, 120, 131.25, 131.25, 79.5, 59.5);
  c.frames = 5;
  c.occluder_fraction = 0.2;
  return c;
}

}  // namespace

TEST_CASE("a written synthetic sequence loads back with its frames, poses and depths", "[synth]") {
  const auto dir = test::temp_dir("synth_roundtrip");
  const Mesh mesh = builtin_demo_mesh();
  const SynthConfig config = small_config();
  int calls = 0;
  const Synthesizer synthesizer(mesh, config);
  const Sequence written = write_synthetic_sequence(dir, mesh, config, [&](int index, const SynthFrame& frame) {
    CHECK(index == calls);
    CHECK(frame.timestamp == synthesizer.frame(index).timestamp);
    ++calls;
  });
  CHECK(calls == config.frames);
  CHECK(written.frames.size() == static_cast<size_t>(config.frames));
  CHECK(std::filesystem::exists(dir / "sequence.json"));
  CHECK(std::filesystem::exists(dir / "depth_000004.png"));

  const Sequence loaded = load_sequence(dir);
  CHECK(loaded.format == "depthtrack");
  CHECK(loaded.camera.width == 160);
  CHECK(loaded.camera.fx == Approx(131.25));
  CHECK(loaded.metres_per_unit == Approx(config.metres_per_unit));
  REQUIRE(loaded.frames.size() == static_cast<size_t>(config.frames));
  const Synthesizer synth(mesh, config);
  for (size_t i = 0; i < loaded.frames.size(); ++i) {
    const SynthFrame frame = synth.frame(static_cast<int>(i));
    CHECK(loaded.frames[i].timestamp == Approx(frame.timestamp).margin(1e-9));
    REQUIRE(loaded.frames[i].ground_truth.has_value());
    CHECK(translation_error(*loaded.frames[i].ground_truth, frame.ground_truth) < 1e-9);
    CHECK(rotation_error(*loaded.frames[i].ground_truth, frame.ground_truth) < 1e-6);
    const DepthImage depth = loaded.load_depth(i);
    REQUIRE(depth.width() == frame.depth.width());
    REQUIRE(depth.height() == frame.depth.height());
    long mismatched = 0;
    for (size_t p = 0; p < depth.data().size(); ++p) {
      const float a = depth.data()[p], b = frame.depth.data()[p];
      const bool ok = DepthImage::is_valid(a) ? DepthImage::is_valid(b) && std::abs(a - b) <= config.metres_per_unit
                                              : !DepthImage::is_valid(b);
      mismatched += !ok;
    }
    CHECK(mismatched == 0);
  }
}

TEST_CASE("depthtrack synth writes a sequence and explains its options", "[synth]") {
  const auto dir = test::temp_dir("synth_cli");
  const auto [status, output] = test::run_cli(
      "synth --builtin --frames 4 --resolution 160x120 --occluder 0.25 --seed 3 --out " + (dir / "seq").string(),
      dir / "log.txt");
  INFO(output);
  REQUIRE(status == 0);
  CHECK(output.find("4 frames") != std::string::npos);
  const Sequence loaded = load_sequence(dir / "seq");
  CHECK(loaded.frames.size() == 4);
  CHECK(loaded.camera.width == 160);
  CHECK(loaded.camera.fx == Approx(131.25));

  const auto [help_status, help] = test::run_cli("synth --help", dir / "help.txt");
  CHECK(help_status == 0);
  for (const char* option : {"--out", "--mesh", "--unit-scale", "--builtin", "--frames", "--rate", "--occluder",
                             "--seed", "--resolution", "--background"})
    CHECK(help.find(option) != std::string::npos);
}

TEST_CASE("depthtrack synth reports bad arguments as errors", "[synth]") {
  const auto dir = test::temp_dir("synth_cli_errors");
  const auto [no_object, out1] = test::run_cli("synth --out " + (dir / "a").string(), dir / "1.txt");
  CHECK(no_object == 1);
  CHECK(out1.find("--builtin") != std::string::npos);
  const auto [bad_size, out2] =
      test::run_cli("synth --builtin --resolution 640by480 --out " + (dir / "b").string(), dir / "2.txt");
  CHECK(bad_size == 1);
  CHECK(out2.find("640by480") != std::string::npos);
  const auto [bad_fraction, out3] =
      test::run_cli("synth --builtin --occluder 0.95 --out " + (dir / "c").string(), dir / "3.txt");
  CHECK(bad_fraction == 1);
  CHECK(out3.find("occluder_fraction") != std::string::npos);
}
