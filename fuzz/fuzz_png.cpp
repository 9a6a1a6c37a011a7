// DepthImage::load_png on arbitrary bytes.
#include <depthtrack/depth_image.hpp>
#include <depthtrack/error.hpp>

#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = depthtrack::fuzz::write_input("depth.png", data, size);
  try {
    const auto image = depthtrack::DepthImage::load_png(path, 0.001);
    (void)image.valid_count();
  } catch (const depthtrack::Error&) {
  }
  return 0;
}
