// load_sequence on a YCB-Video folder whose gt.json is arbitrary bytes, beside one valid depth PNG.
#include <depthtrack/depth_image.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/sequence.hpp>

#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const auto dir = [] {
    const auto d = depthtrack::fuzz::scratch_dir() / "ycb-video";
    std::filesystem::create_directories(d);
    depthtrack::DepthImage(8, 6).save_png(d / "000001-depth.png", 0.0001);
    return d;
  }();
  depthtrack::fuzz::write_input("ycb-video/gt.json", data, size);
  try {
    const auto sequence = depthtrack::load_sequence(dir);
    (void)sequence.frames.size();
  } catch (const depthtrack::Error&) {
  }
  return 0;
}
