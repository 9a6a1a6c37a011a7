#pragma once
// The compute device the [compute] tests run on: DEPTHTRACK_TEST_DEVICE (default "opencl").
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <depthtrack/error.hpp>
#include <iostream>
#include <memory>
#include <string>

#include "compute/queue.hpp"

namespace depthtrack::test {

inline std::string test_device_selector() {
  const char* env = std::getenv("DEPTHTRACK_TEST_DEVICE");
  return env && *env ? env : "opencl";
}

// The test device's queue, or nullptr after printing "SKIPPED: ..." (a ctest skip) when none opens,
// as on a machine without any OpenCL platform.
inline std::unique_ptr<compute::Queue> test_queue() {
  try {
    return compute::open_device(test_device_selector());
  } catch (const Error& e) {
    std::cout << "SKIPPED: no compute device: " << e.what() << "\n";
    return nullptr;
  }
}

inline bool contains_nocase(std::string text, std::string word) {
  const auto lower = [](std::string& s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  };
  lower(text);
  lower(word);
  return text.find(word) != std::string::npos;
}

}  // namespace depthtrack::test
