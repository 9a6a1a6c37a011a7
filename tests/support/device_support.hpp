#pragma once
// The compute device that device tests run on: DEPTHTRACK_TEST_DEVICE (default "opencl", the best
// OpenCL device; PoCL in CI), or a skip when none can be opened.
#include <cstdlib>
#include <iostream>
#include <string>

#include "compute/queue.hpp"

namespace depthtrack::test {

inline std::string device_selector() {
  const char* env = std::getenv("DEPTHTRACK_TEST_DEVICE");
  return env ? env : "opencl";
}

// True when the test device opens; otherwise prints "SKIPPED: ..." (a ctest skip) and returns false.
inline bool device_available() {
  try {
    compute::open_device(device_selector());
    return true;
  } catch (const std::exception& e) {
    std::cout << "SKIPPED: no compute device '" << device_selector() << "': " << e.what() << "\n";
    return false;
  }
}

// False, after printing a ctest skip, in a build without the GL atlas (DEPTHTRACK_WITH_GL=OFF);
// defined in build_options.cpp, the one test file that sees the build's options.
bool gl_built();

}  // namespace depthtrack::test
