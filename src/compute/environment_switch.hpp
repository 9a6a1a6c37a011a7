#pragma once
// The environment's on/off switches of the compute layer (DEPTHTRACK_PROGRAM_CACHE,
// DEPTHTRACK_CUDA_GRAPHS, DEPTHTRACK_CUDA_STREAM_PRIORITIES): unset or any other value leaves the
// feature on.
#include <cstdlib>
#include <string_view>

namespace depthtrack::compute {

// Whether environment variable `name` turns its feature off: "0", "off", "OFF" or "no".
inline bool turned_off_by_environment(const char* name) {
  const char* value = std::getenv(name);
  if (!value) return false;
  const std::string_view v(value);
  return v == "0" || v == "off" || v == "OFF" || v == "no";
}

}  // namespace depthtrack::compute
