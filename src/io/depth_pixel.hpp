#pragma once
// Internal to the I/O layer: one pixel of a sensor image in metres, by the rules DepthImage and
// DepthView share (so that both paths give the same image, bit for bit).
#include <cmath>
#include <cstdint>
#include <depthtrack/error.hpp>
#include <limits>
#include <sstream>

namespace depthtrack::io {

// NaN, 0 and +inf are the sensors' spellings of "no measurement": NaN. A negative depth (or -inf)
// is an InputError naming pixel (u, v).
inline float metres_pixel(float z, size_t u, size_t v) {
  if (std::isnan(z) || z == 0.0f || z == std::numeric_limits<float>::infinity())
    return std::numeric_limits<float>::quiet_NaN();
  if (z < 0.0f) {
    std::ostringstream message;
    message << "depth image pixel (" << u << ", " << v << ") has negative depth " << z << " m";
    throw InputError(message.str());
  }
  return z;
}

// metres = value * metres_per_unit, 0 = no measurement (NaN).
inline float units_pixel(uint16_t value, double metres_per_unit) {
  return value == 0 ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(value * metres_per_unit);
}

}  // namespace depthtrack::io
