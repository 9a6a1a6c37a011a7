// tracker_config_from_json on arbitrary text: what `--config FILE` and TrackerConfig.from_json read.
#include <cstddef>
#include <cstdint>
#include <depthtrack/config_file.hpp>
#include <depthtrack/error.hpp>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const auto config = depthtrack::tracker_config_from_json(std::string(reinterpret_cast<const char*>(data), size));
    (void)config.particles;
  } catch (const depthtrack::Error&) {
  }
  return 0;
}
