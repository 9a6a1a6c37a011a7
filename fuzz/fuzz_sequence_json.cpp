// load_sequence on a folder whose sequence.json is arbitrary bytes, then every frame's depth.
#include <depthtrack/error.hpp>
#include <depthtrack/sequence.hpp>

#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto dir = depthtrack::fuzz::scratch_dir() / "depthtrack-sequence";
  std::filesystem::create_directories(dir);
  depthtrack::fuzz::write_input("depthtrack-sequence/sequence.json", data, size);
  try {
    const auto sequence = depthtrack::load_sequence(dir);
    for (size_t i = 0; i < sequence.frames.size() && i < 4; ++i) (void)sequence.load_depth(i);
  } catch (const depthtrack::Error&) {
  }
  return 0;
}
