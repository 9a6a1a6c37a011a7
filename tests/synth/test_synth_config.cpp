// Every impossible synthesizer setting is an InputError that names it.
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/synth.hpp>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>

#include "support.hpp"

using namespace depthtrack;
using Catch::Matchers::Contains;

namespace {
// Runs f and expects an InputError whose message contains text.
template <class F>
void check_input_error(F f, const std::string& text) {
  try {
    f();
    FAIL("no InputError; expected one mentioning '" << text << "'");
  } catch (const InputError& e) {
    CHECK_THAT(std::string(e.what()), Contains(text));
  }
}

void check_rejected(const std::function<void(SynthConfig&)>& spoil, const std::string& name) {
  SynthConfig config;
  spoil(config);
  INFO("spoiled: " << name);
  check_input_error([&] { Synthesizer(builtin_demo_mesh(), config); }, name);
}
}  // namespace

TEST_CASE("invalid synthesizer settings are rejected with their name", "[synth]") {
  check_rejected([](SynthConfig& c) { c.frames = 0; }, "frames = 0");
  check_rejected([](SynthConfig& c) { c.rate = 0; }, "rate = 0");
  check_rejected([](SynthConfig& c) { c.rate = std::numeric_limits<double>::quiet_NaN(); }, "rate");
  check_rejected([](SynthConfig& c) { c.occluder_fraction = 0.95; }, "occluder_fraction = 0.95");
  check_rejected([](SynthConfig& c) { c.occluder_fraction = -0.1; }, "occluder_fraction = -0.1");
  check_rejected([](SynthConfig& c) { c.metres_per_unit = 0; }, "metres_per_unit = 0");
  check_rejected([](SynthConfig& c) { c.camera.fx = -1; }, "fx");
  check_rejected([](SynthConfig& c) { c.camera.width = 0; }, "image size");
  check_rejected([](SynthConfig& c) { c.sensor.disparity_step = 0; }, "disparity_step");
  check_rejected([](SynthConfig& c) { c.sensor.edge_dropout = 1.5; }, "edge_dropout = 1.5");
  check_rejected([](SynthConfig& c) { c.sensor.max_depth = 0.1; }, "max_depth");
  check_rejected([](SynthConfig& c) { c.trajectory.period = 0; }, "period");
}

TEST_CASE("an empty mesh and out-of-range frames are rejected", "[synth]") {
  check_input_error([] { Synthesizer(Mesh{}, SynthConfig{}); }, "mesh");
  SynthConfig config;
  config.frames = 3;
  const Synthesizer synth(builtin_demo_mesh(), config);
  check_input_error([&] { synth.frame(3); }, "frame 3");
  check_input_error([&] { synth.frame(-1); }, "frame -1");
}

TEST_CASE("a bad configuration writes nothing", "[synth]") {
  const auto dir = test::temp_dir("synth_bad_config") / "out";
  SynthConfig config;
  config.frames = -2;
  check_input_error([&] { write_synthetic_sequence(dir, builtin_demo_mesh(), config); }, "frames = -2");
  CHECK(!std::filesystem::exists(dir));
  config = SynthConfig{};
  config.metres_per_unit = 0.00001;  // 16 bits would end at 0.66 m
  check_input_error([&] { write_synthetic_sequence(dir, builtin_demo_mesh(), config); }, "metres_per_unit");
  CHECK(!std::filesystem::exists(dir));
}
