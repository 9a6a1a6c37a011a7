// Hostile sizes at the input surfaces: nesting, file sizes, image sizes and mesh header counts beyond
// sane bounds are refused with an error naming them, never a crash (a stack overflow, a pixel count
// wrapping 32 bits) nor an allocation failure.
#include <catch2/catch.hpp>
#include <depthtrack/config_file.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/sequence.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_support.hpp"
#include "support.hpp"

using namespace depthtrack;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

std::string nested_arrays(size_t depth) {
  return "{\"particles\": " + std::string(depth, '[') + std::string(depth, ']') + "}";
}

}  // namespace

TEST_CASE("a configuration nested 200,000 deep is refused by its depth, not a stack overflow", "[config][limits]") {
  CHECK_THROWS_WITH(tracker_config_from_json(nested_arrays(200000)), Contains("nested deeper than 64 levels"));
  // 64 levels parse; the value is then the wrong type, named in a short message.
  CHECK_THROWS_WITH(tracker_config_from_json(nested_arrays(63)),
                    Contains("'particles' must be an integer, got an array [...] (1 elements)"));
  const auto dir = test::temp_dir("limits_config");
  std::ofstream(dir / "deep.json") << nested_arrays(200000);
  const auto [status, output] =
      test::run_cli("config --config " + (dir / "deep.json").string() + " --dump", dir / "log.txt");
  INFO(output.substr(0, 400));
  CHECK(status == 1);
  CHECK_THAT(output, Contains("deep.json") && Contains("nested deeper than 64 levels"));
}

TEST_CASE("a configuration error quotes at most a short excerpt of the value", "[config][limits]") {
  const std::string long_text(100000, 'x');
  try {
    tracker_config_from_json("{\"particles\": \"" + long_text + "\"}");
    FAIL("accepted a string as the particle count");
  } catch (const InputError& e) {
    const std::string message = e.what();
    CHECK_THAT(message, Contains("'particles' must be an integer, got a string \"xxxx"));
    CHECK_THAT(message, Contains("..."));
    CHECK(message.size() < 200);
  }
}

TEST_CASE("a configuration that is a device or larger than 16 MiB is refused before it is read", "[config][limits]") {
  if (fs::exists("/dev/zero"))
    CHECK_THROWS_WITH(load_tracker_config("/dev/zero"),
                      Contains("configuration file '/dev/zero' is not a regular file"));
  const auto dir = test::temp_dir("limits_config_size");
  {
    std::ofstream big(dir / "big.json");
    big << "{\"particles\": 10" << std::string(17 << 20, ' ') << "}";
  }
  CHECK_THROWS_WITH(load_tracker_config(dir / "big.json"),
                    Contains("big.json") && Contains("more than the 16 MiB allowed"));
  std::ofstream(dir / "small.json") << "{\"particles\": 10}";
  CHECK(load_tracker_config(dir / "small.json").particles == 10);
}

TEST_CASE("image sizes beyond the limits are refused before any allocation", "[camera][limits]") {
  CHECK_THROWS_WITH(Camera::make(65536, 65537, 525, 525, 32767.5, 32768), Contains("65536x65537 is larger than"));
  CHECK_THROWS_WITH(Camera::make(16384, 16384, 13000, 13000, 8191.5, 8191.5),
                    Contains("67108864 pixels in all"));  // 2^28 pixels: each side allowed, the product not
  CHECK_NOTHROW(Camera::make(8192, 8192, 6600, 6600, 4095.5, 4095.5));
  TrackerConfig config;
  config.width = 100000;
  config.height = 100000;
  CHECK_THROWS_WITH(config.validate(), Contains("working resolution 100000x100000 is larger than"));
  const auto dir = test::temp_dir("limits_synth_size");
  for (const char* size : {"65536x65537", "100000x100000"}) {
    const auto [status, output] =
        test::run_cli(std::string("synth --builtin --frames 1 --resolution ") + size + " --out " + (dir / "s").string(),
                      dir / "log.txt");
    INFO(output);
    CHECK(status == 1);
    CHECK_THAT(output, Contains(size) && Contains("is larger than the 16384 pixels a side"));
  }
}

TEST_CASE("a PLY header claiming more vertices than the file holds is refused before allocating", "[io][limits]") {
  const auto dir = test::temp_dir("limits_ply");
  std::ofstream(dir / "huge.ply") << "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n"
                                     "property float x\nproperty float y\nproperty float z\nelement face 1\n"
                                     "property list uchar int vertex_indices\nend_header\n"
                                  << std::string(64, '\0');
  CHECK_THROWS_WITH(Mesh::load(dir / "huge.ply"), Contains("huge.ply") &&
                                                      Contains("header claims more than it holds") &&
                                                      Contains("4000000000 vertex"));
  // An honest ASCII file of one triangle is read.
  std::ofstream(dir / "one.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                    "end_header\n0 0 0\n0.1 0 0\n0 0.1 0\n3 0 1 2\n";
  CHECK(Mesh::load(dir / "one.ply").triangles.size() == 1);
}
