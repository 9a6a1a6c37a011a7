// DepthImage::load_float32 on arbitrary bytes; the first byte picks the claimed size.
#include <depthtrack/depth_image.hpp>
#include <depthtrack/error.hpp>

#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const int width = (data[0] & 15) - 1, height = (data[0] >> 4) - 1;  // -1 .. 14: bad sizes too
  const auto path = depthtrack::fuzz::write_input("depth.f32", data + 1, size - 1);
  try {
    const auto image = depthtrack::DepthImage::load_float32(path, width, height);
    (void)image.valid_count();
  } catch (const depthtrack::Error&) {
  }
  return 0;
}
